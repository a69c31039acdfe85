#include "encoder/src/train/view_evaluation.h"

#include <algorithm>

#include "encoder/src/metrics/colour_fitted_psnr.h"
#include "encoder/src/metrics/psnr.h"
#include "encoder/src/metrics/ssim.h"
#include "encoder/src/raster/splat_renderer.h"

namespace m4d {

Status RenderView(const GaussianModel& model, const Camera& camera, const RenderSettings& settings,
                  RenderContext* context, Image* image) {
  const M4dGaussians layer = GaussianView(model);
  M4D_RETURN_IF_ERROR(RenderForward(camera, &layer, 1, settings, nullptr, context));
  Reshape(camera.width, camera.height, 3, image);
  std::transform(context->color.begin(), context->color.end(), image->pixels.begin(),
                 [](float v) { return std::clamp(v, 0.0f, 1.0f); });
  return Status::Ok();
}

Status EvaluateViews(const GaussianModel& model, const TrainingViews& views,
                     const RenderSettings& settings, RenderContext* context,
                     EvaluationResult* result) {
  M4D_RETURN_IF_ERROR(CheckTrainingViews(views));
  RenderContext local;
  if (context == nullptr) context = &local;
  EvaluationResult out;
  Image rendered;
  SsimWorkspace workspace;
  for (int v = 0; v < views.size(); ++v) {
    M4D_RETURN_IF_ERROR(RenderView(model, views.cameras[v], settings, context, &rendered));
    ViewQuality q;
    M4D_RETURN_IF_ERROR(Psnr(rendered, views.images[v], &q.psnr));
    M4D_RETURN_IF_ERROR(SsimZeroPadded(rendered, views.images[v], &q.ssim, nullptr, &workspace));
    M4D_RETURN_IF_ERROR(ColourFittedPsnr(rendered, views.images[v], &q.colour_fitted_psnr));
    out.mean_psnr += q.psnr;
    out.mean_ssim += q.ssim;
    out.mean_colour_fitted_psnr += q.colour_fitted_psnr;
    out.views.push_back(q);
  }
  if (!out.views.empty()) {
    out.mean_psnr /= static_cast<double>(out.views.size());
    out.mean_ssim /= static_cast<double>(out.views.size());
    out.mean_colour_fitted_psnr /= static_cast<double>(out.views.size());
  }
  *result = std::move(out);
  return Status::Ok();
}

}  // namespace m4d
