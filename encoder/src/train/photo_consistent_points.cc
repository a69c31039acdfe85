#include "train/photo_consistent_points.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <utility>
#include <vector>

#include "common/thread_pool.h"
#include "train/scene_extent.h"
#include "train/training_random.h"

namespace m4d {
namespace {

constexpr size_t kMaxCandidates = size_t{1} << 26;

// World point on the ray of pixel (u, v) of the camera, at camera-space depth `depth`.
void BackProject(const Camera& camera, float u, float v, float depth, float out[3]) {
  const float c[3] = {(u - camera.cx) / camera.fx * depth - camera.translation[0],
                      (v - camera.cy) / camera.fy * depth - camera.translation[1],
                      depth - camera.translation[2]};
  const float* r = camera.rotation;  // world-to-camera, row-major: apply its transpose
  for (int a = 0; a < 3; ++a) out[a] = r[a] * c[0] + r[3 + a] * c[1] + r[6 + a] * c[2];
}

// The pixel's colour if the camera sees the point (in front of its near plane, inside).
bool Sample(const Camera& camera, const Image& image, const float p[3], float rgb[3]) {
  const float* r = camera.rotation;
  const float* t = camera.translation;
  const float z = r[6] * p[0] + r[7] * p[1] + r[8] * p[2] + t[2];
  if (!(z > camera.near_plane)) return false;
  const float x = r[0] * p[0] + r[1] * p[1] + r[2] * p[2] + t[0];
  const float y = r[3] * p[0] + r[4] * p[1] + r[5] * p[2] + t[1];
  const float u = camera.fx * x / z + camera.cx, v = camera.fy * y / z + camera.cy;
  if (!(u >= 0 && v >= 0 && u < camera.width && v < camera.height)) return false;
  const float* px = image.row(static_cast<int>(v)) + 3 * static_cast<int>(u);
  std::copy_n(px, 3, rgb);
  return true;
}

struct Candidate {
  float position[3];
  float colour[3];
  float score;  // colour variance across the views; infinity when seen by too few
};

// Mean colour and its variance (summed over channels) across the views that see the point.
void Score(const TrainingViews& views, int min_views, Candidate* c) {
  double sum[3] = {0, 0, 0}, squares = 0;
  int seen = 0;
  for (int v = 0; v < views.size(); ++v) {
    float rgb[3];
    if (!Sample(views.cameras[v], views.images[v], c->position, rgb)) continue;
    ++seen;
    for (int k = 0; k < 3; ++k) {
      sum[k] += rgb[k];
      squares += static_cast<double>(rgb[k]) * rgb[k];
    }
  }
  c->score = INFINITY;
  if (seen < min_views) return;
  double variance = squares / seen;
  for (int k = 0; k < 3; ++k) {
    const double mean = sum[k] / seen;
    c->colour[k] = static_cast<float>(mean);
    variance -= mean * mean;
  }
  c->score = static_cast<float>(std::max(variance, 0.0));
}

Status CheckOptions(const TrainingViews& views, const PhotoConsistencyOptions& o) {
  if (views.size() == 0) return Status(M4D_ERR_INVALID_ARG, "photo-consistent points: no views");
  if (o.candidates_per_point < 1 || o.min_views < 0 || !(o.far_extents > 0) ||
      !std::isfinite(o.far_extents)) {
    return Status(M4D_ERR_INVALID_ARG, "photo-consistent points: bad options");
  }
  if (o.points * static_cast<size_t>(o.candidates_per_point) > kMaxCandidates) {
    return LimitError("photo-consistent points: too many candidates");
  }
  return Status::Ok();
}

}  // namespace

Status PhotoConsistentPoints(const TrainingViews& views, const PhotoConsistencyOptions& options,
                             PointCloud* points) {
  M4D_RETURN_IF_ERROR(CheckOptions(views, options));
  const float extent = CameraSceneBounds(views.cameras).extent;
  if (!(extent > 0)) return Status(M4D_ERR_INVALID_ARG, "photo-consistent points: zero extent");
  const int min_views = options.min_views > 0 ? options.min_views : std::max(2, views.size() / 2);
  std::vector<Candidate> candidates(options.points *
                                    static_cast<size_t>(options.candidates_per_point));
  TrainingRandom rng(options.seed);
  for (Candidate& c : candidates) {
    const Camera& camera = views.cameras[rng.Below(static_cast<uint32_t>(views.size()))];
    const float near = camera.near_plane, far = std::max(near * 2, options.far_extents * extent);
    const float inverse = 1.0f / far + (1.0f / near - 1.0f / far) * rng.Uniform();
    BackProject(camera, rng.Uniform() * camera.width, rng.Uniform() * camera.height, 1.0f / inverse,
                c.position);
  }
  ThreadPool pool(options.threads);
  ParallelForChunks(&pool, candidates.size(), 4096, [&](size_t begin, size_t end, int) {
    for (size_t i = begin; i < end; ++i) Score(views, min_views, &candidates[i]);
  });
  std::vector<uint32_t> order(candidates.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = static_cast<uint32_t>(i);
  const auto better = [&](uint32_t a, uint32_t b) {
    return candidates[a].score < candidates[b].score ||
           (candidates[a].score == candidates[b].score && a < b);
  };
  const size_t keep = std::min(options.points, order.size());
  std::nth_element(order.begin(), order.begin() + keep, order.end(), better);
  std::sort(order.begin(), order.begin() + keep);  // candidate order: independent of the sort
  *points = PointCloud();
  for (size_t k = 0; k < keep; ++k) {
    const Candidate& c = candidates[order[k]];
    if (!std::isfinite(c.score)) continue;
    points->positions.insert(points->positions.end(), c.position, c.position + 3);
    for (float colour : c.colour) points->colors.push_back(std::clamp(colour, 0.0f, 1.0f));
  }
  return Status::Ok();
}

}  // namespace m4d
