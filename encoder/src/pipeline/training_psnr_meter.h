// TrainingPsnrMeter: the mean PSNR over a frame's training views of the GOP's static set with
// a dynamic set, the measure of the inter-frame mode decisions and of the adaptive GOP. The
// static set and the cameras stay for the GOP, so each view's static-only render and the
// static set's projection are made once (encoder/src/train/frozen_layer_views.h); a measure then
// renders only the tiles the dynamic set reaches (encoder/src/raster/tile_focus.h) and takes every
// other tile's error from the static render, which is what the whole render holds there. PSNR as
// view_evaluation.h measures it (renders clamped to [0, 1], mean over views), without its SSIM. A
// frame's decisions measure the same set more than once: results are kept for the frame.
#ifndef M4D_ENCODER_PIPELINE_TRAINING_PSNR_METER_H_
#define M4D_ENCODER_PIPELINE_TRAINING_PSNR_METER_H_

#include <vector>

#include "encoder/src/raster/render_context.h"
#include "encoder/src/raster/render_settings.h"
#include "encoder/src/train/frozen_layer_views.h"
#include "encoder/src/train/training_views.h"
#include "sdk/src/common/status.h"
#include "sdk/src/layers/gaussian_set.h"

namespace m4d {

class TrainingPsnrMeter {
 public:
  // static_set must outlive the meter and stay unchanged (the GOP's); static_views is its
  // FrozenLayerViews for the GOP's cameras, made with the same settings, and must outlive the
  // meter too.
  TrainingPsnrMeter(const GaussianSet& static_set, const RenderSettings& settings,
                    FrozenLayerViews* static_views);

  // The training views of the frame being measured (kept by reference until the next call);
  // their cameras must be the GOP's.
  Status StartFrame(const TrainingViews& views);

  // Mean PSNR over the views of the static set with dynamic_set (dB).
  Status Measure(const GaussianSet& dynamic_set, double* psnr);

  // The same over the views listed (indices into the frame's views; not kept).
  Status MeasureViews(const GaussianSet& dynamic_set, const std::vector<int>& views, double* psnr);

 private:
  Status ViewPsnr(const GaussianSet& dynamic_set, int view, double* psnr);

  const GaussianSet& static_set_;
  RenderSettings settings_;
  const TrainingViews* views_ = nullptr;
  RenderContext context_;
  FrozenLayerViews* static_views_;
  std::vector<std::vector<double>> static_error_;  // per view and tile: squared error
  std::vector<double> errors_;                     // scratch: one render's, per tile
  struct Measured {
    GaussianSet set;
    double psnr;
  };
  std::vector<Measured> measured_;
};

}  // namespace m4d

#endif  // M4D_ENCODER_PIPELINE_TRAINING_PSNR_METER_H_
