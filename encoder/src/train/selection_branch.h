// Branches of a selection on held-out training views (prune_share_selection.h,
// rate_weight_selection.h): a shortened schedule trains to a branch point on all views but the
// held-out ones, each candidate setting then continues a copy of it, and the held-out views and
// the coded keyframe's bytes judge the copies.
#ifndef M4D_ENCODER_TRAIN_SELECTION_BRANCH_H_
#define M4D_ENCODER_TRAIN_SELECTION_BRANCH_H_

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "encoder/src/train/keyframe_trainer.h"
#include "encoder/src/train/training_views.h"
#include "sdk/src/common/status.h"

namespace m4d {

// What a branch ends with.
struct BranchResult {
  double psnr = 0;  // the held-out training views' mean PSNR (dB)
  size_t gaussians = 0;
  size_t bytes = 0;  // the model coded as a keyframe set at the trainer's quantization
};

// Progress of one branch, named by `run`.
using SelectionProgress = std::function<void(const std::string& run, const TrainingProgress&)>;

// What `candidate` may lose against `reference` (dB): `max_loss_per_halving_db` times the
// halvings of the coded bytes (0 when they did not fall).
double AllowedLoss(const BranchResult& reference, const BranchResult& candidate,
                   double max_loss_per_halving_db);

// The views not in `held_out` (sorted), and those in it.
void SplitViews(const TrainingViews& views, const std::vector<int>& held_out, TrainingViews* fit,
                TrainingViews* validation);

// The trunk every branch copies: holds the views `held_out` (indices into `views`, sorted) out,
// records their capture indices in `cameras`, and trains `initial` with `schedule` on the
// others up to iteration `branch_point` (progress named `run`).
Status TrainTrunk(const TrainingViews& views, const std::vector<int>& held_out,
                  const GaussianModel& initial, const KeyframeTrainingOptions& schedule,
                  int branch_point, const std::string& run, const SelectionProgress& progress,
                  std::vector<int>* cameras, TrainingViews* validation, KeyframeTrainer* trunk);

// Runs `trainer` to the end of its schedule and measures it on `validation`.
Status RunBranch(const std::string& run, const TrainingViews& validation,
                 const SelectionProgress& progress, KeyframeTrainer* trainer, BranchResult* result);

// A branch's name in progress lines: `label` and the candidate's value ("share 0.1").
std::string BranchName(const char* label, double value);

// `count` scaled by `fraction`, at least 1 where it was positive.
int ScaledCount(int count, double fraction);

}  // namespace m4d

#endif  // M4D_ENCODER_TRAIN_SELECTION_BRANCH_H_
