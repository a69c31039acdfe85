#include "encoder/src/run/quality_curve.h"

#include <cstdio>
#include <utility>

#include "encoder/src/io/atomic_file.h"
#include "encoder/src/train/view_evaluation.h"

namespace m4d {

QualityCurve::QualityCurve(std::vector<double> marks, TrainingViews held_out,
                           RenderSettings settings)
    : marks_(std::move(marks)),
      held_out_(std::move(held_out)),
      settings_(settings),
      start_(Clock::now()) {}

double QualityCurve::Minutes() const {
  return std::chrono::duration<double>(Clock::now() - start_ - paused_).count() / 60.0;
}

Status QualityCurve::Evaluate(int iteration, size_t gaussians,
                              const std::function<Status(EvaluationResult*)>& evaluate) {
  const Clock::time_point begin = Clock::now();
  QualityCurvePoint point;
  point.minutes = Minutes();
  point.iteration = iteration;
  point.gaussians = gaussians;
  EvaluationResult quality;
  M4D_RETURN_IF_ERROR(evaluate(&quality));
  point.psnr = quality.mean_psnr;
  points_.push_back(point);
  paused_ += Clock::now() - begin;
  return Status::Ok();
}

Status QualityCurve::Observe(KeyframeTrainer* trainer) {
  if (next_mark_ >= marks_.size() || Minutes() < marks_[next_mark_]) return Status::Ok();
  while (next_mark_ < marks_.size() && Minutes() >= marks_[next_mark_]) ++next_mark_;
  return Evaluate(trainer->iteration(), trainer->model().size(),
                  [&](EvaluationResult* quality) { return trainer->Evaluate(held_out_, quality); });
}

Status QualityCurve::Finish(const GaussianModel& model, int iteration) {
  return Evaluate(iteration, model.size(), [&](EvaluationResult* quality) {
    return EvaluateViews(model, held_out_, settings_, nullptr, quality);
  });
}

Status QualityCurve::WriteCsv(const std::string& path) const {
  std::string text = "minutes,iteration,gaussians,psnr\n";
  for (const QualityCurvePoint& p : points_) {
    char line[96];
    std::snprintf(line, sizeof(line), "%.3f,%d,%zu,%.3f\n", p.minutes, p.iteration, p.gaussians,
                  p.psnr);
    text += line;
  }
  return WriteFileAtomically(path, reinterpret_cast<const uint8_t*>(text.data()), text.size());
}

void QualityCurve::Print() const {
  std::printf("%-28s %8s %10s %10s %9s\n", "quality over time", "minutes", "iteration", "Gaussians",
              "held out");
  for (const QualityCurvePoint& p : points_) {
    std::printf("%-28s %8.2f %10d %10zu %6.2f dB\n", "", p.minutes, p.iteration, p.gaussians,
                p.psnr);
  }
}

}  // namespace m4d
