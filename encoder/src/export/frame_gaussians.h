// A decoded frame (the SDK's public M4dFrame) as one GaussianSet, for export to the formats
// other tools read: the static layer's Gaussians, then the dynamic layer's.
#ifndef M4D_ENCODER_EXPORT_FRAME_GAUSSIANS_H_
#define M4D_ENCODER_EXPORT_FRAME_GAUSSIANS_H_

#include <cstdint>

#include "m4d/m4d.h"
#include "sdk/src/common/status.h"
#include "sdk/src/layers/gaussian_set.h"

namespace m4d {

// Concatenates the layers of `frame` selected by `layers` (M4D_LAYER_* bits). A layer of a
// lower SH degree (a caller background) gets zero higher coefficients. M4D_ERR_INVALID_ARG for
// inconsistent layer arrays.
Status GaussianSetFromFrame(const M4dFrame& frame, uint32_t layers, GaussianSet* out);

}  // namespace m4d

#endif  // M4D_ENCODER_EXPORT_FRAME_GAUSSIANS_H_
