// Quality of a model on a set of views: each view rendered (clamped to [0, 1], as images are
// saved) and compared with its image by PSNR and SSIM (the zero-padded convention of the
// reference 3DGS evaluation, see metrics/ssim.h); means over views as papers report them.
// Beside them, the PSNR with each view's colour fitted (metrics/colour_fitted_psnr.h): how
// much of a held-out camera's error is its exposure and white balance.
#ifndef M4D_ENCODER_TRAIN_VIEW_EVALUATION_H_
#define M4D_ENCODER_TRAIN_VIEW_EVALUATION_H_

#include <vector>

#include "encoder/src/raster/render_context.h"
#include "encoder/src/raster/render_settings.h"
#include "encoder/src/train/gaussian_model.h"
#include "encoder/src/train/training_views.h"
#include "sdk/src/common/status.h"

namespace m4d {

struct ViewQuality {
  double psnr = 0;  // dB
  double ssim = 0;
  double colour_fitted_psnr = 0;  // dB
};

struct EvaluationResult {
  std::vector<ViewQuality> views;
  double mean_psnr = 0;
  double mean_ssim = 0;
  double mean_colour_fitted_psnr = 0;
};

// settings: threads, SH degree and background of the renders. context: reused render
// buffers (may be null).
Status EvaluateViews(const GaussianModel& model, const TrainingViews& views,
                     const RenderSettings& settings, RenderContext* context,
                     EvaluationResult* result);

// Renders the model from `camera` into *image (RGB, clamped to [0, 1]).
Status RenderView(const GaussianModel& model, const Camera& camera, const RenderSettings& settings,
                  RenderContext* context, Image* image);

}  // namespace m4d

#endif  // M4D_ENCODER_TRAIN_VIEW_EVALUATION_H_
