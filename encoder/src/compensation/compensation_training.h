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
#include <functional>
#include <vector>

#include "encoder/src/compensation/compensation_candidates.h"
#include "encoder/src/train/encode_context.h"
#include "encoder/src/train/frozen_layer_views.h"
#include "encoder/src/train/learning_rate_schedule.h"
#include "encoder/src/train/training_views.h"
#include "sdk/src/common/status.h"
#include "sdk/src/layers/gaussian_set.h"

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
  EncodeContext context;
  // The early decision: the probe given to TrainCompensation measures the gain of the
  // Gaussians trained so far after probe_iteration / 2 and probe_iteration iterations (0:
  // never). When the gain extrapolated along that line to the last iteration stays under
  // probe_min_gain, the training ends there. The gain rises ever more slowly once the
  // candidates have settled (default scene, Panoptic basketball, the test scene of
  // compensation_training_test.cc), so the line overestimates where the training would end.
  int probe_iteration = 20;
  double probe_min_gain = 0.1;  // dB
};

// Measures the gain (dB) of the frame as compensated so far: the moved set without its
// removed Gaussians, and the added ones (pruned as at the end, not yet checked for being seen).
using CompensationProbe =
    std::function<Status(const GaussianSet& kept, const GaussianSet& added, double* gain)>;

struct CompensationResult {
  GaussianSet added;             // the optimised compensated Gaussians that survived
  std::vector<uint8_t> removed;  // per Gaussian of the moved set: 1 = removed
  size_t pruned_added = 0;       // candidates removed by the sparsity pruning
  size_t removed_unseen = 0;     // moved Gaussians removed because no view sees them
  double color_loss = 0;         // mean L_color over the last pass through the views
  bool abandoned = false;        // the early decision ended the training: nothing added
  double probed_gain = 0;        // the probe's last measure (dB; 0: none)
};

// Mean over the training views of each moved Gaussian's view-space gradient norm (the
// reference's NDC units), rendering static_set and moved together: the replication measure
// of compensation_candidates.h. static_views as CompensationSharing's. blend_weight, when
// given, receives each moved Gaussian's blend weight summed over the views, from the same
// renders.
Status MeasureViewspaceGradients(const TrainingViews& views, const GaussianSet& static_set,
                                 const GaussianSet& moved, int sh_degree,
                                 const EncodeContext& encode, std::vector<float>* mean_gradient,
                                 FrozenLayerViews* static_views = nullptr,
                                 std::vector<float>* blend_weight = nullptr);

// What the caller can share with TrainCompensation, each optional.
struct CompensationSharing {
  // static_set's for these views' cameras, kept for the GOP (null: made for the call).
  FrozenLayerViews* static_views = nullptr;
  // Each moved Gaussian's blend weight over the views, MeasureViewspaceGradients' (null:
  // rendered for the call).
  const std::vector<float>* moved_blend_weight = nullptr;
  CompensationProbe probe;  // takes the early decision (null: none)
};

Status TrainCompensation(const TrainingViews& views, const GaussianSet& static_set,
                         const GaussianSet& moved, const CompensationCandidates& candidates,
                         const CompensationOptions& options, CompensationResult* result,
                         const CompensationSharing& sharing = CompensationSharing());

}  // namespace m4d

#endif  // M4D_ENCODER_COMPENSATION_COMPENSATION_TRAINING_H_
