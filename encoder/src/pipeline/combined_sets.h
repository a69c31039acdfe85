// Gaussian sets put together: a frame's dynamic set with its compensation (kept Gaussians, then
// the added ones, the order the decoder appends them in), and a model of a frame's two layers
// for the renders and trainings that take a GaussianModel.
#ifndef M4D_ENCODER_PIPELINE_COMBINED_SETS_H_
#define M4D_ENCODER_PIPELINE_COMBINED_SETS_H_

#include <cstdint>
#include <vector>

#include "encoder/src/train/gaussian_model.h"
#include "sdk/src/common/status.h"
#include "sdk/src/layers/gaussian_set.h"

namespace m4d {

// Appends the Gaussians of `from` not flagged in `removed` (null: all of them) to *to.
void AppendKept(const GaussianSet& from, const std::vector<uint8_t>* removed, GaussianSet* to);

// A model of both sets, static first, at the static set's SH degree.
Status CombinedModel(const GaussianSet& static_set, const GaussianSet& dynamic_set,
                     GaussianModel* model);

}  // namespace m4d

#endif  // M4D_ENCODER_PIPELINE_COMBINED_SETS_H_
