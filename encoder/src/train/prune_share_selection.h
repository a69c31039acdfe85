// Prune share selection: how much of a keyframe importance pruning may remove
// (KeyframeTrainingOptions::importance_prune_share) is a property of the capture, not a constant. A
// large share halves the default scene's keyframe for little on its held-out camera, yet Panoptic
// basketball and a sparse rig lose as much or more at much smaller shares; and the training views
// cannot tell these apart (they lose least where the held-out camera loses most:
// docs/results/2026-11-30-readme-notebook.md, "Keyframes pruned by importance"). So training views
// are held out (one in ten, at least one; one view alone was too noisy on Panoptic): the schedule,
// shortened, runs on the others to where pruning happens; from there one branch goes on unpruned
// and one per candidate share, largest first. The first candidate whose held-out views lose at most
// max_loss_per_halving_db for every halving of the keyframe's coded bytes (against the unpruned
// branch) is the share. The bound is a rate trade: it is a fraction of what the rate points give up
// in the stream per halving of its bytes, so a share within it is the cheaper way to the same
// bytes. The held-out views predict what the test cameras lose
// (docs/results/2026-11-30-readme-notebook.md, "The prune share is chosen per capture").
#ifndef M4D_ENCODER_TRAIN_PRUNE_SHARE_SELECTION_H_
#define M4D_ENCODER_TRAIN_PRUNE_SHARE_SELECTION_H_

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "encoder/src/train/gaussian_model.h"
#include "encoder/src/train/keyframe_bits_selection.h"
#include "encoder/src/train/keyframe_stage.h"
#include "encoder/src/train/keyframe_trainer.h"
#include "encoder/src/train/selection_branch.h"
#include "encoder/src/train/training_views.h"
#include "sdk/src/common/status.h"
#include "sdk/src/render/camera.h"

namespace m4d {

struct PruneShareSelectionOptions {
  std::vector<float> shares = {0.1f, 0.03f, 0.01f};  // candidates, tried largest first
  // Held-out views' PSNR a candidate may lose against the unpruned branch, in dB per halving
  // of the coded bytes (log2 of the unpruned branch's bytes over the candidate's, each model
  // coded as a keyframe at the options' quantization and SH degree).
  double max_loss_per_halving_db = 0.5;
  // With fewer training views none is held out and the share is 0: a sparse rig trained on
  // one view less is another capture, and it is where pruning costs most.
  int min_views = 6;
  // One view held out per this many training views (rounded, at least one).
  int views_per_held_out = 10;
  // The shortened schedule: this share of the keyframe's iterations, same proportions.
  double schedule_fraction = 0.5;
  // Each branch runs this share of the shortened schedule's iterations after the prune, not
  // the rest of it: the branches were two thirds of `m4d train`'s time on Panoptic, and the
  // held-out views rank the candidates as the full branches did
  // (docs/results/2026-11-29-quality-per-minute.md).
  double branch_fraction = 0.125;
};

struct PruneShareTrial : BranchResult {
  float share = 0;
};

struct PruneShareChoice {
  float share = 0;
  std::vector<int> validation_cameras;  // the capture's indices of the views held out (none:
                                        // too few views, share 0)
  PruneShareTrial unpruned;
  std::vector<PruneShareTrial> trials;  // the candidates tried, in order
  // The branch of the share chosen, for the keyframe bits to be judged on the same views
  // (keyframe_bits_selection.h); empty when no view was held out.
  HeldOutModel branch;
};

// What `pruned` may lose against `unpruned` (dB): the bound per halving times the halvings of
// the coded bytes (0 when they did not fall).
double AllowedLoss(const PruneShareTrial& unpruned, const PruneShareTrial& pruned,
                   const PruneShareSelectionOptions& selection);

// The `count` views held out, in increasing order: those whose camera centres have the least
// summed distance to the others (the first on ties), views the others surround as a held-out
// camera usually is.
std::vector<int> ValidationViews(const std::vector<Camera>& cameras, int count);

// How many of `views` training views SelectPruneShare holds out (0: too few to select).
int HeldOutCount(int views, const PruneShareSelectionOptions& selection);

// `options` with every iteration count scaled by `fraction` (at least 1 where it was
// positive), without quantization-aware iterations or importance pruning by share.
KeyframeTrainingOptions ShortenedSchedule(const KeyframeTrainingOptions& options, double fraction);

// The selection's shared part: the shortened schedule, trained from a start on all views but
// the held-out ones to the iteration before the prune, and its branch without a prune. Each
// candidate share continues a copy of `trainer`.
struct PruneShareTrunk {
  KeyframeTrainer trainer;
  TrainingViews validation;             // the held-out views
  std::vector<int> validation_cameras;  // their capture indices
  PruneShareTrial unpruned;
  HeldOutModel unpruned_branch;  // that branch's model, with the held-out views
};

// Trains `trunk` from `initial` (built without the held-out views, as HeldOutStart builds it)
// with `options` on `views`, its progress named `run`. Needs held-out views
// (HeldOutCount(views.size(), selection) > 0).
Status TrainPruneShareTrunk(const TrainingViews& views, const GaussianModel& initial,
                            const KeyframeTrainingOptions& options,
                            const PruneShareSelectionOptions& selection, const std::string& run,
                            const SelectionProgress& progress, PruneShareTrunk* trunk);

// Chooses the share from `trunk`: the first candidate whose branch is within the bound.
Status SelectPruneShare(const PruneShareTrunk& trunk, const PruneShareSelectionOptions& selection,
                        const SelectionProgress& progress, PruneShareChoice* choice);

// Chooses the share for a keyframe trained with `options` on `views`; `initial` is the model
// to start from, built without the held-out views (ValidationViews) as InitialKeyframeModel
// builds it. progress may be null.
Status SelectPruneShare(const TrainingViews& views, const GaussianModel& initial,
                        const KeyframeTrainingOptions& options,
                        const PruneShareSelectionOptions& selection,
                        const SelectionProgress& progress, PruneShareChoice* choice);

// The initial model built from the `views` that `selection` does not hold out (an empty model
// when it holds none out), and the options a keyframe trains with from that start
// (OptionsForStart, random_start_schedule.h).
Status HeldOutStart(const Capture& capture, const TrainingViews& views,
                    const KeyframeTrainingOptions& options,
                    const PruneShareSelectionOptions& selection, GaussianModel* initial,
                    KeyframeTrainingOptions* trained);

// The capture's training views of `frame`, and HeldOutStart's model and options.
Status LoadSelectionInputs(const Capture& capture, int frame,
                           const KeyframeTrainingOptions& options,
                           const PruneShareSelectionOptions& selection, TrainingViews* views,
                           GaussianModel* initial, KeyframeTrainingOptions* trained);

// The same from the capture's frame: loads its training views and the initial model.
Status SelectPruneShare(const Capture& capture, int frame, const KeyframeTrainingOptions& options,
                        const PruneShareSelectionOptions& selection,
                        const SelectionProgress& progress, PruneShareChoice* choice);

}  // namespace m4d

#endif  // M4D_ENCODER_TRAIN_PRUNE_SHARE_SELECTION_H_
