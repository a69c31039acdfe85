#include "encoder/src/train/rate_weight_selection.h"

#include <string>

namespace m4d {

Status SelectRateWeight(const TrainingViews& views, const GaussianModel& initial,
                        const KeyframeTrainingOptions& options,
                        const RateWeightSelectionOptions& selection,
                        const SelectionProgress& progress, RateWeightChoice* choice) {
  *choice = RateWeightChoice();
  const PruneShareSelectionOptions& held = selection.held_out;
  const int held_out_count = HeldOutCount(views.size(), held);
  if (held_out_count == 0 || options.quantization_aware_iterations <= 0) return Status::Ok();
  // The shortened schedule with its share of quantization-aware iterations, where the rate
  // term acts, and the prune the keyframe will have.
  KeyframeTrainingOptions schedule = ShortenedSchedule(options, held.schedule_fraction);
  schedule.quantization_aware_iterations =
      ScaledCount(options.quantization_aware_iterations, held.schedule_fraction);
  schedule.importance_prune_share = options.importance_prune_share;
  schedule.rate_weight = 0.0;
  const int branch_point = schedule.iterations - schedule.quantization_aware_iterations;
  if (branch_point < 1) {
    return Status(M4D_ERR_INVALID_ARG, "rate weight selection: no iteration before the rate term");
  }
  TrainingViews validation;
  KeyframeTrainer trunk;
  M4D_RETURN_IF_ERROR(TrainTrunk(views, ValidationViews(views.cameras, held_out_count), initial,
                                 schedule, branch_point, "without rate term", progress,
                                 &choice->validation_cameras, &validation, &trunk));
  KeyframeTrainer without = trunk;
  M4D_RETURN_IF_ERROR(
      RunBranch("without rate term", validation, progress, &without, &choice->without));
  for (double weight : selection.weights) {
    KeyframeTrainer branch = trunk;
    branch.SetRateWeight(weight);
    RateWeightTrial trial;
    trial.weight = weight;
    M4D_RETURN_IF_ERROR(
        RunBranch(BranchName("rate weight", weight), validation, progress, &branch, &trial));
    choice->trials.push_back(trial);
    if (choice->without.psnr - trial.psnr <=
        AllowedLoss(choice->without, trial, held.max_loss_per_halving_db)) {
      choice->weight = weight;
      break;
    }
  }
  return Status::Ok();
}

Status SelectRateWeight(const Capture& capture, int frame, const KeyframeTrainingOptions& options,
                        const RateWeightSelectionOptions& selection,
                        const SelectionProgress& progress, RateWeightChoice* choice) {
  TrainingViews views;
  GaussianModel initial;
  KeyframeTrainingOptions trained;
  M4D_RETURN_IF_ERROR(
      LoadSelectionInputs(capture, frame, options, selection.held_out, &views, &initial, &trained));
  return SelectRateWeight(views, initial, trained, selection, progress, choice);
}

}  // namespace m4d
