// Gaussian compensation of an inter frame (paper sections 3.4 and 4.3): the candidates of
// compensation_candidates.h are optimised (every attribute) over the static set and the moved
// dynamic set, which stay fixed, under
//   L_s3 = L_color + lambda_3 |dG|_0.
// The L0 norm is not differentiable. Its relaxation here is the sum of the added Gaussians'
// opacity logits: every Gaussian feels the same constant pull lambda_3 towards transparency
// however faint it already is (a sum of opacities would stop pulling near zero), and only
// the colour loss holds useful ones up. The norm becomes real by removing added Gaussians
// whose opacity falls below a threshold (every prune_interval iterations and at the end) or
// that no training view sees. Moved Gaussians that no training view sees any more are removed
// too, so the dynamic set cannot grow without bound over a long GOP.
// In 60 iterations the norm prunes little: Adam moves a logit about one learning rate a step
// whatever lambda_3 is, and replicas start as opaque as their parents (on the default scene
// lambda_3 from 5e-5 to 1e-3 keeps 353 of the same candidates). How many Gaussians an inter
// frame adds is steered by the replication threshold tau_g instead (pipeline/rate_points.h).
#ifndef M4D_ENCODER_COMPENSATION_COMPENSATION_TRAINING_H_
#define M4D_ENCODER_COMPENSATION_COMPENSATION_TRAINING_H_

#include <cstdint>
#include <vector>

#include "common/status.h"
#include "compensation/compensation_candidates.h"
#include "layers/gaussian_set.h"
#include "render/frozen_layer_views.h"
#include "train/learning_rate_schedule.h"
#include "train/training_views.h"

namespace m4d {

struct CompensationOptions {
  int iterations = 60;
  double sparsity_weight = 5e-5;  // lambda_3
  float prune_opacity = 0.005f;   // added Gaussians below are removed
  int prune_interval = 25;
  // Blend weight (sum of alpha T over all training views) below which a Gaussian counts as
  // unseen.
  float min_blend_weight = 1e-3f;
  GaussianLearningRates learning_rates;  // the position rate at its initial value
  float scene_extent = 1.0f;
  double ssim_weight = 0.2;
  int sh_degree = 3;
  float background[3] = {0, 0, 0};
  int threads = 0;
  uint64_t seed = 0;
};

struct CompensationResult {
  GaussianSet added;             // the optimised compensated Gaussians that survived
  std::vector<uint8_t> removed;  // per Gaussian of the moved set: 1 = removed
  size_t pruned_added = 0;       // candidates removed by the sparsity pruning
  size_t removed_unseen = 0;     // moved Gaussians removed because no view sees them
  double color_loss = 0;         // mean L_color over the last pass through the views
};

// Mean over the training views of each moved Gaussian's view-space gradient norm (the
// reference's NDC units), rendering static_set and moved together: the replication measure
// of compensation_candidates.h. static_views as for TrainCompensation.
Status MeasureViewspaceGradients(const TrainingViews& views, const GaussianSet& static_set,
                                 const GaussianSet& moved, int sh_degree, const float* background,
                                 int threads, std::vector<float>* mean_gradient,
                                 FrozenLayerViews* static_views = nullptr);

// static_views, when given, is static_set's for these views' cameras, kept for the GOP
// (null: made for this call).
Status TrainCompensation(const TrainingViews& views, const GaussianSet& static_set,
                         const GaussianSet& moved, const CompensationCandidates& candidates,
                         const CompensationOptions& options, CompensationResult* result,
                         FrozenLayerViews* static_views = nullptr);

}  // namespace m4d

#endif  // M4D_ENCODER_COMPENSATION_COMPENSATION_TRAINING_H_
