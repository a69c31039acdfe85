// The conversions between the SDK's two containers of Gaussians, in one place. A GaussianSet
// owns a layer's Gaussians (allocated through the caller's hooks); an M4dGaussians (m4d.h) is
// a view of one: what the public API returns and what every renderer draws. Both hold the
// values as coded (log scales, opacity logits, unnormalised quaternions w, x, y, z, SH
// [gaussian][k][r, g, b]). Several layers (a frame's static and dynamic sets) render together,
// their Gaussians indexed in concatenation order. The encoder's trainable GaussianModel has
// its view and its conversions to and from a GaussianSet in gaussian_model.h.
#ifndef M4D_SDK_LAYERS_GAUSSIAN_VIEWS_H_
#define M4D_SDK_LAYERS_GAUSSIAN_VIEWS_H_

#include "m4d/m4d.h"
#include "sdk/src/common/status.h"
#include "sdk/src/layers/gaussian_set.h"

namespace m4d {

// The view of a set: pointers into it, NULL when it is empty.
M4dGaussians GaussianView(const GaussianSet& set);

// Appends a public layer's Gaussians to `out`; a layer of a lower SH degree than out's gets
// zero higher coefficients. M4D_ERR_INVALID_ARG for inconsistent layer arrays.
Status AppendLayer(const M4dGaussians& layer, GaussianSet* out);

}  // namespace m4d

#endif  // M4D_SDK_LAYERS_GAUSSIAN_VIEWS_H_
