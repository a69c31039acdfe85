// Held-out quality against the wall time of a command: `m4d train --curve` evaluates the
// model on the test cameras as training passes given minutes, so one run gives the whole
// quality-over-time curve. The clock stops while it evaluates.
#ifndef M4D_ENCODER_RUN_QUALITY_CURVE_H_
#define M4D_ENCODER_RUN_QUALITY_CURVE_H_

#include <chrono>
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "encoder/src/raster/render_context.h"
#include "encoder/src/train/gaussian_model.h"
#include "encoder/src/train/keyframe_trainer.h"
#include "encoder/src/train/training_views.h"
#include "sdk/src/common/status.h"

namespace m4d {

struct QualityCurvePoint {
  double minutes = 0;  // the command's wall time, evaluation excluded
  int iteration = 0;
  size_t gaussians = 0;
  double psnr = 0;  // mean over the held-out views (dB)
};

class QualityCurve {
 public:
  // Starts the clock; the model is evaluated on `held_out` once each of `marks` (minutes,
  // increasing) has passed.
  QualityCurve(std::vector<double> marks, TrainingViews held_out, RenderSettings settings);

  // Evaluates the trainer's model as it renders it if a mark has passed since the last call.
  Status Observe(KeyframeTrainer* trainer);
  // Evaluates the final model, whatever the clock says.
  Status Finish(const GaussianModel& model, int iteration);

  const std::vector<QualityCurvePoint>& points() const { return points_; }
  // Minutes, iteration, Gaussians, PSNR; one line per point, atomically.
  Status WriteCsv(const std::string& path) const;
  void Print() const;

 private:
  using Clock = std::chrono::steady_clock;
  double Minutes() const;
  // Adds a point measured by `evaluate`.
  Status Evaluate(int iteration, size_t gaussians,
                  const std::function<Status(EvaluationResult*)>& evaluate);

  std::vector<double> marks_;
  size_t next_mark_ = 0;
  TrainingViews held_out_;
  RenderSettings settings_;
  Clock::time_point start_;
  Clock::duration paused_{};
  std::vector<QualityCurvePoint> points_;
};

}  // namespace m4d

#endif  // M4D_ENCODER_RUN_QUALITY_CURVE_H_
