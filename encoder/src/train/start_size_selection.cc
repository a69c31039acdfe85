#include "encoder/src/train/start_size_selection.h"

#include <cmath>
#include <string>
#include <utility>

namespace m4d {

bool ChoosesStartSize(const Capture& capture, int views, const KeyframeTrainingOptions& options,
                      const StartSizeSelectionOptions& selection) {
  return capture.initial_points.size() == 0 && !options.random_initialisation &&
         HeldOutCount(views, selection.held_out) > 0 && selection.sweep_shares.size() > 1;
}

double RateAdjustedPsnr(const BranchResult& reference, const BranchResult& candidate,
                        double max_loss_per_halving_db) {
  if (candidate.bytes == 0 || reference.bytes == 0) return candidate.psnr;
  const double halvings =
      std::log2(static_cast<double>(reference.bytes) / static_cast<double>(candidate.bytes));
  return candidate.psnr + max_loss_per_halving_db * halvings;
}

Status SelectStartSize(const Capture& capture, int frame, const KeyframeTrainingOptions& options,
                       const StartSizeSelectionOptions& selection,
                       const SelectionProgress& progress, StartSizeChoice* choice,
                       PruneShareTrunk* trunk) {
  *choice = StartSizeChoice();
  choice->sweep_share = options.sweep_share;
  M4D_RETURN_IF_ERROR(ValidateTrainingOptions(options));
  // The views are loaded only where their count can decide.
  if (capture.initial_points.size() > 0 || options.random_initialisation) return Status::Ok();
  TrainingViews views;
  M4D_RETURN_IF_ERROR(LoadTrainingViews(capture, frame, capture.TrainCameras(), &views));
  if (!ChoosesStartSize(capture, views.size(), options, selection)) return Status::Ok();
  const double per_halving = selection.held_out.max_loss_per_halving_db;
  double best_score = 0;
  for (float share : selection.sweep_shares) {
    KeyframeTrainingOptions candidate = options;
    candidate.sweep_share = share;
    GaussianModel initial;
    KeyframeTrainingOptions trained;
    M4D_RETURN_IF_ERROR(
        HeldOutStart(capture, views, candidate, selection.held_out, &initial, &trained));
    PruneShareTrunk trained_trunk;
    M4D_RETURN_IF_ERROR(TrainPruneShareTrunk(views, initial, trained, selection.held_out,
                                             BranchName("sweep share", share), progress,
                                             &trained_trunk));
    StartSizeTrial trial;
    static_cast<BranchResult&>(trial) = trained_trunk.unpruned;
    trial.sweep_share = share;
    trial.start_points = initial.size();
    const BranchResult& reference = choice->trials.empty() ? trial : choice->trials.front();
    trial.score = RateAdjustedPsnr(reference, trial, per_halving);
    const bool best = choice->trials.empty() || trial.score > best_score;
    choice->trials.push_back(trial);
    if (best) {
      best_score = trial.score;
      choice->sweep_share = share;
      choice->validation_cameras = trained_trunk.validation_cameras;
      *trunk = std::move(trained_trunk);
    }
  }
  return Status::Ok();
}

}  // namespace m4d
