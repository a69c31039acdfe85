#include "encoder/src/pipeline/held_out_evaluation.h"

#include <chrono>

#include "encoder/src/pipeline/combined_sets.h"
#include "encoder/src/train/training_views.h"
#include "encoder/src/train/view_evaluation.h"

namespace m4d {

Status EvaluateHeldOut(const Capture& capture, int frame, const GaussianSet& static_set,
                       const GaussianSet& dynamic_set, const RenderSettings& settings,
                       const HeldOutViewCallback& held_out_view, FrameReport* report) {
  report->static_count = static_set.size();
  report->dynamic_count = dynamic_set.size();
  if (capture.test_cameras.empty()) return Status::Ok();
  const auto start = std::chrono::steady_clock::now();
  TrainingViews test;
  M4D_RETURN_IF_ERROR(LoadTrainingViews(capture, frame, capture.test_cameras, &test));
  GaussianModel model;
  M4D_RETURN_IF_ERROR(CombinedModel(static_set, dynamic_set, &model));
  EvaluationResult result;
  RenderContext context;
  M4D_RETURN_IF_ERROR(EvaluateViews(model, test, settings, &context, &result));
  if (held_out_view) {
    Image render;
    M4D_RETURN_IF_ERROR(RenderView(model, test.cameras[0], settings, &context, &render));
    held_out_view(frame, test.images[0], render);
  }
  report->held_out = true;
  report->psnr = result.mean_psnr;
  report->ssim = result.mean_ssim;
  report->seconds.evaluation =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return Status::Ok();
}

}  // namespace m4d
