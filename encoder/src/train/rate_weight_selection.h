// Rate weight selection: how much the keyframe's rate term may pull its attributes towards likelier
// levels (KeyframeTrainingOptions::rate_weight, lambda_k) is a property of the capture. On Panoptic
// basketball a rate weight codes the keyframe smaller and renders its held-out cameras better (a
// regulariser on a sparse real rig), where on the default scene a smaller weight already costs more
// quality than the bytes it saves are worth (docs/results/2026-11-30-readme-notebook.md,
// "Rate-aware keyframe training"; docs/results/2026-11-30-comment-measurements.md). So, as for the
// prune share (prune_share_selection.h), training views are held out: the shortened schedule runs
// on the others to where quantization-aware training starts, from there one branch goes on without
// the rate term and one per candidate weight, largest first. The first whose held-out views lose at
// most the bound per halving of the coded keyframe is the weight, else 0.
#ifndef M4D_ENCODER_TRAIN_RATE_WEIGHT_SELECTION_H_
#define M4D_ENCODER_TRAIN_RATE_WEIGHT_SELECTION_H_

#include <vector>

#include "encoder/src/capture/capture.h"
#include "encoder/src/train/gaussian_model.h"
#include "encoder/src/train/keyframe_trainer.h"
#include "encoder/src/train/prune_share_selection.h"
#include "encoder/src/train/selection_branch.h"
#include "encoder/src/train/training_views.h"
#include "sdk/src/common/status.h"

namespace m4d {

struct RateWeightSelectionOptions {
  std::vector<double> weights = {1e-3, 3e-4};  // candidates, tried largest first
  // The views held out, the shortened schedule and the loss bound, as the prune share's.
  PruneShareSelectionOptions held_out;
};

struct RateWeightTrial : BranchResult {
  double weight = 0;
};

struct RateWeightChoice {
  double weight = 0;
  std::vector<int> validation_cameras;  // none: too few views, or no quantization-aware
                                        // iterations for a rate term to act in; weight 0
  RateWeightTrial without;              // the branch without the rate term
  std::vector<RateWeightTrial> trials;  // the candidates tried, in order
};

// Chooses the weight for a keyframe trained with `options` (its importance_prune_share the one
// it will be trained with) on `views`; `initial` as SelectPruneShare's. progress may be null.
Status SelectRateWeight(const TrainingViews& views, const GaussianModel& initial,
                        const KeyframeTrainingOptions& options,
                        const RateWeightSelectionOptions& selection,
                        const SelectionProgress& progress, RateWeightChoice* choice);

// The same from the capture's frame: loads its training views and the initial model.
Status SelectRateWeight(const Capture& capture, int frame, const KeyframeTrainingOptions& options,
                        const RateWeightSelectionOptions& selection,
                        const SelectionProgress& progress, RateWeightChoice* choice);

}  // namespace m4d

#endif  // M4D_ENCODER_TRAIN_RATE_WEIGHT_SELECTION_H_
