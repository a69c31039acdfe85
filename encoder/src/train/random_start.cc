#include "encoder/src/train/random_start.h"

#include <algorithm>
#include <cmath>

#include "encoder/src/train/training_random.h"
#include "encoder/src/train/view_sampling.h"

namespace m4d {
namespace {

void Push(const float p[3], const float rgb[3], PointCloud* points) {
  points->positions.insert(points->positions.end(), p, p + 3);
  points->colors.insert(points->colors.end(), rgb, rgb + 3);
}

}  // namespace

Status ViewedRandomPoints(const TrainingViews& views, const float lo[3], const float hi[3],
                          const RandomStartOptions& options, PointCloud* points) {
  *points = PointCloud();
  for (int a = 0; a < 3; ++a) {
    if (!std::isfinite(lo[a]) || !std::isfinite(hi[a]) || !(lo[a] <= hi[a])) {
      return Status(M4D_ERR_INVALID_ARG, "random start: bad box");
    }
  }
  if (views.size() == 0 || options.min_views < 1 || options.max_draws_per_point < 1) {
    return Status(M4D_ERR_INVALID_ARG, "random start: no views or bad options");
  }
  const int min_views = std::min(options.min_views, views.size());
  TrainingRandom rng(options.seed);
  auto draw = [&](float p[3]) {
    for (int a = 0; a < 3; ++a) p[a] = lo[a] + (hi[a] - lo[a]) * rng.Uniform();
  };
  const size_t max_draws = options.points * static_cast<size_t>(options.max_draws_per_point);
  double mean[3] = {0, 0, 0};
  for (size_t d = 0; d < max_draws && points->size() < options.points; ++d) {
    float p[3], rgb[3];
    draw(p);
    if (!MeanViewColour(views, p, min_views, rgb)) continue;
    Push(p, rgb, points);
    for (int c = 0; c < 3; ++c) mean[c] += rgb[c];
  }
  const size_t viewed = points->size();
  float fill[3] = {0.5f, 0.5f, 0.5f};
  if (viewed > 0) {
    for (int c = 0; c < 3; ++c) fill[c] = static_cast<float>(mean[c] / viewed);
  }
  while (points->size() < options.points) {
    float p[3];
    draw(p);
    Push(p, fill, points);
  }
  return Status::Ok();
}

}  // namespace m4d
