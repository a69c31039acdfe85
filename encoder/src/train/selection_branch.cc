#include "encoder/src/train/selection_branch.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

#include "encoder/src/layers/gaussian_set_writer.h"
#include "encoder/src/train/view_evaluation.h"
#include "sdk/src/common/byte_writer.h"

namespace m4d {

double AllowedLoss(const BranchResult& reference, const BranchResult& candidate,
                   double max_loss_per_halving_db) {
  if (candidate.bytes == 0 || reference.bytes <= candidate.bytes) return 0.0;
  const double halvings =
      std::log2(static_cast<double>(reference.bytes) / static_cast<double>(candidate.bytes));
  return max_loss_per_halving_db * halvings;
}

void SplitViews(const TrainingViews& views, const std::vector<int>& held_out, TrainingViews* fit,
                TrainingViews* validation) {
  for (int v = 0; v < views.size(); ++v) {
    const bool out = std::binary_search(held_out.begin(), held_out.end(), v);
    TrainingViews* into = out ? validation : fit;
    into->camera_indices.push_back(views.camera_indices[static_cast<size_t>(v)]);
    into->cameras.push_back(views.cameras[static_cast<size_t>(v)]);
    into->images.push_back(views.images[static_cast<size_t>(v)]);
  }
}

Status TrainTrunk(const TrainingViews& views, const std::vector<int>& held_out,
                  const GaussianModel& initial, const KeyframeTrainingOptions& schedule,
                  int branch_point, const std::string& run, const SelectionProgress& progress,
                  std::vector<int>* cameras, TrainingViews* validation, KeyframeTrainer* trunk) {
  for (int v : held_out) cameras->push_back(views.camera_indices[static_cast<size_t>(v)]);
  TrainingViews fit;
  SplitViews(views, held_out, &fit, validation);
  M4D_RETURN_IF_ERROR(trunk->Init(schedule, std::move(fit), initial));
  return trunk->TrainUntil(branch_point, [&](const TrainingProgress& p) {
    if (progress) progress(run, p);
  });
}

Status RunBranch(const std::string& run, const TrainingViews& validation,
                 const SelectionProgress& progress, KeyframeTrainer* trainer,
                 BranchResult* result) {
  M4D_RETURN_IF_ERROR(trainer->Train([&](const TrainingProgress& p) {
    if (progress) progress(run, p);
  }));
  EvaluationResult quality;
  M4D_RETURN_IF_ERROR(trainer->Evaluate(validation, &quality));
  result->psnr = quality.mean_psnr;
  result->gaussians = trainer->model().size();
  GaussianSet set;
  M4D_RETURN_IF_ERROR(ModelToGaussianSet(trainer->model(), trainer->model().sh_degree, &set));
  std::vector<uint8_t> bytes;
  ByteWriter writer(&bytes);
  M4D_RETURN_IF_ERROR(WriteGaussianSet(set, trainer->options().quantization, &writer));
  result->bytes = bytes.size();
  return Status::Ok();
}

std::string BranchName(const char* label, double value) {
  char text[64];
  std::snprintf(text, sizeof(text), "%s %g", label, value);
  return text;
}

int ScaledCount(int count, double fraction) {
  if (count <= 0) return count;
  return std::max(1, static_cast<int>(std::lround(count * fraction)));
}

}  // namespace m4d
