// Importance pruning (LightGaussian, Fan et al. 2023, without its volume term): a Gaussian's
// importance is its blending weight alpha T summed over every pixel of the training views,
// what it adds to the images whatever its colour. Densification stops at the views'
// gradients, not at what each Gaussian contributes; the least important Gaussians left then
// cost the keyframe bytes (about 10 each) for what the fine-tuning that follows restores.
#ifndef M4D_ENCODER_TRAIN_IMPORTANCE_PRUNING_H_
#define M4D_ENCODER_TRAIN_IMPORTANCE_PRUNING_H_

#include <cstdint>
#include <vector>

#include "encoder/src/raster/render_context.h"
#include "encoder/src/raster/render_settings.h"
#include "encoder/src/raster/splat_backward.h"
#include "encoder/src/train/gaussian_model.h"
#include "encoder/src/train/training_views.h"
#include "sdk/src/common/status.h"

namespace m4d {

// Each Gaussian's blending weight summed over the views (one render and one backward pass
// per view; `context` and `workspace` are reused buffers).
Status BlendingWeights(const GaussianModel& model, const TrainingViews& views,
                       const RenderSettings& settings, RenderContext* context,
                       BackwardWorkspace* workspace, std::vector<double>* weights);

// keep[i] = 0 for the least important Gaussians whose weights sum to at most `share` of the
// total (ties broken by index) and for every Gaussian whose weight is below `min_weight`
// (pixels: what it covers in all the views together), 1 for the others; at most max_fraction
// of the Gaussians are removed, the least important first.
std::vector<uint8_t> KeepImportant(const std::vector<double>& weights, double share,
                                   double min_weight = 0.0, double max_fraction = 1.0);

}  // namespace m4d

#endif  // M4D_ENCODER_TRAIN_IMPORTANCE_PRUNING_H_
