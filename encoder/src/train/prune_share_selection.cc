#include "encoder/src/train/prune_share_selection.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <utility>

#include "encoder/src/train/random_start_schedule.h"

namespace m4d {

double AllowedLoss(const PruneShareTrial& unpruned, const PruneShareTrial& pruned,
                   const PruneShareSelectionOptions& selection) {
  return AllowedLoss(static_cast<const BranchResult&>(unpruned),
                     static_cast<const BranchResult&>(pruned), selection.max_loss_per_halving_db);
}

std::vector<int> ValidationViews(const std::vector<Camera>& cameras, int count) {
  std::vector<std::array<float, 3>> centres(cameras.size());
  for (size_t c = 0; c < cameras.size(); ++c) CameraCentre(cameras[c], centres[c].data());
  std::vector<double> sums(cameras.size(), 0.0);
  for (size_t c = 0; c < cameras.size(); ++c) {
    for (const std::array<float, 3>& other : centres) {
      const double dx = centres[c][0] - other[0], dy = centres[c][1] - other[1],
                   dz = centres[c][2] - other[2];
      sums[c] += std::sqrt(dx * dx + dy * dy + dz * dz);
    }
  }
  std::vector<int> order(cameras.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return sums[static_cast<size_t>(a)] < sums[static_cast<size_t>(b)];
  });
  order.resize(std::min(order.size(), static_cast<size_t>(std::max(count, 0))));
  std::sort(order.begin(), order.end());
  return order;
}

int HeldOutCount(int views, const PruneShareSelectionOptions& selection) {
  if (views < std::max(selection.min_views, 2)) return 0;
  const int every = std::max(selection.views_per_held_out, 1);
  return std::clamp((views + every / 2) / every, 1, views - 1);
}

KeyframeTrainingOptions ShortenedSchedule(const KeyframeTrainingOptions& options, double fraction) {
  KeyframeTrainingOptions o = options;
  o.iterations = ScaledCount(options.iterations, fraction);
  o.learning_rates.position.max_steps =
      ScaledCount(options.learning_rates.position.max_steps, fraction);
  o.densify_from = ScaledCount(options.densify_from, fraction);
  o.densify_until = ScaledCount(options.densify_until, fraction);
  o.densify_interval = ScaledCount(options.densify_interval, fraction);
  o.opacity_reset_interval = ScaledCount(options.opacity_reset_interval, fraction);
  o.reset_recovery = ScaledCount(options.reset_recovery, fraction);
  o.sh_degree_interval = ScaledCount(options.sh_degree_interval, fraction);
  o.coarse_to_fine.until = ScaledCount(options.coarse_to_fine.until, fraction);
  o.quantization_aware_iterations = 0;
  o.importance_prune_share = 0.0f;
  return o;
}

Status TrainPruneShareTrunk(const TrainingViews& views, const GaussianModel& initial,
                            const KeyframeTrainingOptions& options,
                            const PruneShareSelectionOptions& selection, const std::string& run,
                            const SelectionProgress& progress, PruneShareTrunk* trunk) {
  const int held_out_count = HeldOutCount(views.size(), selection);
  if (held_out_count == 0) {
    return Status(M4D_ERR_INVALID_ARG, "prune share selection: too few views to hold one out");
  }
  KeyframeTrainingOptions schedule = ShortenedSchedule(options, selection.schedule_fraction);
  if (schedule.densify_until <= 1 || schedule.densify_until > schedule.iterations) {
    return Status(M4D_ERR_INVALID_ARG, "prune share selection: the schedule never prunes");
  }
  // The branches stop early; the learning rates keep the shortened schedule's decay.
  schedule.iterations = std::min(
      schedule.iterations,
      schedule.densify_until + ScaledCount(schedule.iterations, selection.branch_fraction));
  // Shared until the iteration before the prune; each branch is a copy from there.
  M4D_RETURN_IF_ERROR(TrainTrunk(views, ValidationViews(views.cameras, held_out_count), initial,
                                 schedule, schedule.densify_until - 1, run, progress,
                                 &trunk->validation_cameras, &trunk->validation, &trunk->trainer));
  KeyframeTrainer unpruned = trunk->trainer;
  M4D_RETURN_IF_ERROR(RunBranch(run, trunk->validation, progress, &unpruned, &trunk->unpruned));
  trunk->unpruned.share = 0.0f;
  trunk->unpruned_branch.validation = trunk->validation;
  trunk->unpruned_branch.settings = unpruned.Settings();
  trunk->unpruned_branch.model = unpruned.TakeModel();
  return Status::Ok();
}

Status SelectPruneShare(const PruneShareTrunk& trunk, const PruneShareSelectionOptions& selection,
                        const SelectionProgress& progress, PruneShareChoice* choice) {
  *choice = PruneShareChoice();
  choice->validation_cameras = trunk.validation_cameras;
  choice->unpruned = trunk.unpruned;
  choice->branch = trunk.unpruned_branch;
  for (float share : selection.shares) {
    KeyframeTrainer branch = trunk.trainer;
    branch.SetImportancePruneShare(share);
    PruneShareTrial trial;
    trial.share = share;
    M4D_RETURN_IF_ERROR(
        RunBranch(BranchName("share", share), trunk.validation, progress, &branch, &trial));
    choice->trials.push_back(trial);
    if (choice->unpruned.psnr - trial.psnr <= AllowedLoss(choice->unpruned, trial, selection)) {
      choice->share = share;
      choice->branch.settings = branch.Settings();
      choice->branch.model = branch.TakeModel();
      break;
    }
  }
  return Status::Ok();
}

Status SelectPruneShare(const TrainingViews& views, const GaussianModel& initial,
                        const KeyframeTrainingOptions& options,
                        const PruneShareSelectionOptions& selection,
                        const SelectionProgress& progress, PruneShareChoice* choice) {
  *choice = PruneShareChoice();
  if (HeldOutCount(views.size(), selection) == 0) return Status::Ok();
  PruneShareTrunk trunk;
  M4D_RETURN_IF_ERROR(
      TrainPruneShareTrunk(views, initial, options, selection, "unpruned", progress, &trunk));
  return SelectPruneShare(trunk, selection, progress, choice);
}

Status HeldOutStart(const Capture& capture, const TrainingViews& views,
                    const KeyframeTrainingOptions& options,
                    const PruneShareSelectionOptions& selection, GaussianModel* initial,
                    KeyframeTrainingOptions* trained) {
  *trained = options;
  const int held_out_count = HeldOutCount(views.size(), selection);
  if (held_out_count == 0) return Status::Ok();
  TrainingViews fit, validation;
  SplitViews(views, ValidationViews(views.cameras, held_out_count), &fit, &validation);
  std::vector<KeyframeStart> starts;
  M4D_RETURN_IF_ERROR(InitialKeyframeModel(capture, fit, options, initial, &starts));
  *trained = OptionsForStart(options, starts);
  return Status::Ok();
}

Status LoadSelectionInputs(const Capture& capture, int frame,
                           const KeyframeTrainingOptions& options,
                           const PruneShareSelectionOptions& selection, TrainingViews* views,
                           GaussianModel* initial, KeyframeTrainingOptions* trained) {
  M4D_RETURN_IF_ERROR(ValidateTrainingOptions(options));
  M4D_RETURN_IF_ERROR(LoadTrainingViews(capture, frame, capture.TrainCameras(), views));
  return HeldOutStart(capture, *views, options, selection, initial, trained);
}

Status SelectPruneShare(const Capture& capture, int frame, const KeyframeTrainingOptions& options,
                        const PruneShareSelectionOptions& selection,
                        const SelectionProgress& progress, PruneShareChoice* choice) {
  TrainingViews views;
  GaussianModel initial;
  KeyframeTrainingOptions trained;
  M4D_RETURN_IF_ERROR(
      LoadSelectionInputs(capture, frame, options, selection, &views, &initial, &trained));
  return SelectPruneShare(views, initial, trained, selection, progress, choice);
}

}  // namespace m4d
