#include "encoder/src/pipeline/noise_gap.h"

#include <cmath>

#include "encoder/src/pipeline/combined_sets.h"
#include "encoder/src/train/view_evaluation.h"

namespace m4d {

Status MeasureNoiseGap(const Capture& capture, int keyframe, const GaussianSet& static_set,
                       const GaussianSet& dynamic_set, const TrainingViews& next,
                       const TemporalChangeOptions& change_options, const RenderSettings& settings,
                       double* gap) {
  TrainingViews own;
  M4D_RETURN_IF_ERROR(LoadTrainingViews(capture, keyframe, capture.TrainCameras(), &own));
  GaussianModel model;
  M4D_RETURN_IF_ERROR(CombinedModel(static_set, dynamic_set, &model));
  double own_error = 0, next_error = 0;
  size_t pixels = 0;
  RenderContext context;
  Image render;
  for (int v = 0; v < own.size() && v < next.size(); ++v) {
    TemporalChange change;
    M4D_RETURN_IF_ERROR(
        MeasureTemporalChange(own.images[v], next.images[v], change_options, &change));
    M4D_RETURN_IF_ERROR(RenderView(model, own.cameras[v], settings, &context, &render));
    for (size_t p = 0; p < change.mask.size(); ++p) {
      if (change.mask[p] > 0) continue;
      for (int c = 0; c < 3; ++c) {
        const double a = render.pixels[3 * p + c] - own.images[v].pixels[3 * p + c];
        const double b = render.pixels[3 * p + c] - next.images[v].pixels[3 * p + c];
        own_error += a * a;
        next_error += b * b;
      }
      pixels += 3;
    }
  }
  *gap = pixels > 0 && own_error > 0 && next_error > own_error
             ? 10.0 * std::log10(next_error / own_error)
             : 0.0;
  return Status::Ok();
}

}  // namespace m4d
