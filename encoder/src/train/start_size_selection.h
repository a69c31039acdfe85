// Start size selection: how many photo-consistent points a capture without points starts from
// (KeyframeTrainingOptions::sweep_share) is a property of the capture. A tenth of the sweep lifts
// Panoptic basketball's test cameras and takes fewer bytes, yet lowers the default scene's when it
// starts without its points (docs/design/start_size_selection.md). So each candidate start trains
// the prune share selection's trunk (prune_share_selection.h) on all training views but the
// held-out ones, and the held-out views judge the trunks' unpruned branches, rate-adjusted: a
// candidate scores its held-out PSNR plus max_loss_per_halving_db for every halving of the coded
// bytes against the first candidate's. The best score wins (the earlier candidate on ties), and its
// trunk goes on to choose the prune share, so the selection costs one trunk per candidate after the
// first.
#ifndef M4D_ENCODER_TRAIN_START_SIZE_SELECTION_H_
#define M4D_ENCODER_TRAIN_START_SIZE_SELECTION_H_

#include <cstddef>
#include <vector>

#include "encoder/src/capture/capture.h"
#include "encoder/src/train/keyframe_trainer.h"
#include "encoder/src/train/prune_share_selection.h"
#include "encoder/src/train/selection_branch.h"
#include "encoder/src/train/training_views.h"
#include "sdk/src/common/status.h"

namespace m4d {

struct StartSizeSelectionOptions {
  std::vector<float> sweep_shares = {1.0f, 0.1f};  // candidates; the first is the reference
  PruneShareSelectionOptions held_out;  // the views held out, the schedule and the rate trade
};

struct StartSizeTrial : BranchResult {
  float sweep_share = 0;
  size_t start_points = 0;  // the initial model's Gaussians (shell included)
  double score = 0;         // RateAdjustedPsnr against the first trial
};

struct StartSizeChoice {
  float sweep_share = 1.0f;
  std::vector<int> validation_cameras;  // none: no choice made (see ChoosesStartSize)
  std::vector<StartSizeTrial> trials;   // one per candidate, in order
};

// Whether a keyframe of `capture` trained with `options` on `views` training views has a start
// size to choose: the capture has no points, the start is not random by request, there are
// views to hold out and more than one candidate.
bool ChoosesStartSize(const Capture& capture, int views, const KeyframeTrainingOptions& options,
                      const StartSizeSelectionOptions& selection);

// `candidate`'s held-out PSNR plus the bound per halving of the coded bytes against
// `reference` (negative halvings where the candidate is larger).
double RateAdjustedPsnr(const BranchResult& reference, const BranchResult& candidate,
                        double max_loss_per_halving_db);

// Chooses the sweep share for a keyframe of `frame` trained with `options`. When a choice is
// made, `trunk` receives the chosen start's trunk for SelectPruneShare; otherwise the choice
// holds options.sweep_share and no trials, and `trunk` is untouched. progress may be null.
Status SelectStartSize(const Capture& capture, int frame, const KeyframeTrainingOptions& options,
                       const StartSizeSelectionOptions& selection,
                       const SelectionProgress& progress, StartSizeChoice* choice,
                       PruneShareTrunk* trunk);

}  // namespace m4d

#endif  // M4D_ENCODER_TRAIN_START_SIZE_SELECTION_H_
