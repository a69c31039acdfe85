#include "encoder/src/train/photo_consistent_points.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "encoder/src/train/scene_extent.h"
#include "encoder/src/train/training_random.h"
#include "encoder/src/train/view_sampling.h"
#include "sdk/src/common/thread_pool.h"

namespace m4d {
namespace {

constexpr size_t kMaxRays = size_t{1} << 24;
constexpr int kMaxDepths = 1024;

// World point on the ray of pixel (u, v) of the camera, at camera-space depth `depth`.
void BackProject(const Camera& camera, float u, float v, float depth, float out[3]) {
  const float c[3] = {(u - camera.cx) / camera.fx * depth - camera.translation[0],
                      (v - camera.cy) / camera.fy * depth - camera.translation[1],
                      depth - camera.translation[2]};
  const float* r = camera.rotation;  // world-to-camera, row-major: apply its transpose
  for (int a = 0; a < 3; ++a) out[a] = r[a] * c[0] + r[3 + a] * c[1] + r[6 + a] * c[2];
}

// Clips [*near, *far] to the camera depths at which the ray of pixel (u, v) is inside the
// options' box (slabs per axis); false when nothing is left.
bool ClipToBox(const Camera& camera, float u, float v, const PhotoConsistencyOptions& options,
               float* near, float* far) {
  if (!options.bounded) return *near < *far;
  float origin[3], at_one[3];
  BackProject(camera, u, v, 0.0f, origin);
  BackProject(camera, u, v, 1.0f, at_one);
  for (int a = 0; a < 3; ++a) {
    const float step = at_one[a] - origin[a];
    if (step == 0.0f) {
      if (origin[a] < options.box_min[a] || origin[a] > options.box_max[a]) return false;
      continue;
    }
    const float t0 = (options.box_min[a] - origin[a]) / step;
    const float t1 = (options.box_max[a] - origin[a]) / step;
    *near = std::max(*near, std::min(t0, t1));
    *far = std::min(*far, std::max(t0, t1));
  }
  return *near < *far;
}

struct Ray {
  int view;
  float u, v;
  float jitter;  // of the depth samples, in [0, 1)
};

struct Found {
  bool ok = false;
  float position[3];
  float colour[3];
};

// Mean squared colour difference to `reference` over the views (but `source`) that see the
// point, and their mean colour; infinity when fewer than min_views see it.
float Score(const TrainingViews& views, int source, const float reference[3], const float p[3],
            int min_views, float mean[3]) {
  double sum = 0, colour[3] = {0, 0, 0};
  int seen = 0;
  for (int v = 0; v < views.size(); ++v) {
    float rgb[3];
    if (v == source || !SampleView(views.cameras[v], views.images[v], p, rgb)) continue;
    ++seen;
    for (int k = 0; k < 3; ++k) {
      const double d = rgb[k] - reference[k];
      sum += d * d;
      colour[k] += rgb[k];
    }
  }
  if (seen < min_views) return INFINITY;
  for (int k = 0; k < 3; ++k) mean[k] = static_cast<float>((colour[k] + reference[k]) / (seen + 1));
  return static_cast<float>(sum / seen);
}

// The ray's most consistent depth, when it stands out from the ray's median score.
Found SweepRay(const TrainingViews& views, const Ray& ray, float far, int min_views,
               const PhotoConsistencyOptions& options, std::vector<float>* scores) {
  const Camera& camera = views.cameras[ray.view];
  const float* reference =
      views.images[ray.view].row(static_cast<int>(ray.v)) + 3 * static_cast<int>(ray.u);
  float near = camera.near_plane;
  if (!ClipToBox(camera, ray.u, ray.v, options, &near, &far)) return Found();
  const float near_inverse = 1.0f / near, far_inverse = 1.0f / far;
  Found found;
  float best = INFINITY;
  scores->clear();
  for (int k = 0; k < options.depths; ++k) {
    const float t = (static_cast<float>(k) + ray.jitter) / static_cast<float>(options.depths);
    const float depth = 1.0f / (near_inverse + (far_inverse - near_inverse) * t);
    float p[3], mean[3];
    BackProject(camera, ray.u, ray.v, depth, p);
    const float score = Score(views, ray.view, reference, p, min_views, mean);
    if (!std::isfinite(score)) continue;
    scores->push_back(score);
    if (score < best) {
      best = score;
      std::copy_n(p, 3, found.position);
      std::copy_n(mean, 3, found.colour);
    }
  }
  if (scores->size() < 3) return Found();
  std::nth_element(scores->begin(), scores->begin() + scores->size() / 2, scores->end());
  found.ok = best < options.distinctness * (*scores)[scores->size() / 2];
  return found;
}

Status CheckOptions(const TrainingViews& views, const PhotoConsistencyOptions& o) {
  if (views.size() == 0) return Status(M4D_ERR_INVALID_ARG, "photo-consistent points: no views");
  if (o.rays_per_point < 1 || o.depths < 3 || o.depths > kMaxDepths || o.min_views < 2 ||
      !(o.far_extents > 0) || !std::isfinite(o.far_extents) || !(o.distinctness > 0) ||
      (o.bounded && !(o.box_min[0] <= o.box_max[0] && o.box_min[1] <= o.box_max[1] &&
                      o.box_min[2] <= o.box_max[2]))) {
    return Status(M4D_ERR_INVALID_ARG, "photo-consistent points: bad options");
  }
  if (o.points * static_cast<size_t>(o.rays_per_point) > kMaxRays) {
    return LimitError("photo-consistent points: too many rays");
  }
  if (o.ray_masks != nullptr) {
    if (o.ray_masks->size() != static_cast<size_t>(views.size())) {
      return Status(M4D_ERR_INVALID_ARG, "photo-consistent points: one mask per view");
    }
    for (int v = 0; v < views.size(); ++v) {
      const Camera& c = views.cameras[v];
      if ((*o.ray_masks)[v].size() != static_cast<size_t>(c.width) * c.height) {
        return Status(M4D_ERR_INVALID_ARG, "photo-consistent points: a mask's size");
      }
    }
  }
  return Status::Ok();
}

// (view, pixel index) of every pixel a ray may start from.
std::vector<std::pair<int, uint32_t>> RayPixels(const TrainingViews& views,
                                                const std::vector<std::vector<float>>& masks) {
  std::vector<std::pair<int, uint32_t>> pixels;
  for (int v = 0; v < views.size(); ++v) {
    for (size_t p = 0; p < masks[v].size(); ++p) {
      if (masks[v][p] > 0.0f) pixels.emplace_back(v, static_cast<uint32_t>(p));
    }
  }
  return pixels;
}

// Rays through uniformly random points of the views, or of their masked pixels.
std::vector<Ray> DrawRays(const TrainingViews& views, const PhotoConsistencyOptions& options) {
  std::vector<Ray> rays(options.points * static_cast<size_t>(options.rays_per_point));
  TrainingRandom rng(options.seed);
  if (options.ray_masks == nullptr) {
    for (Ray& ray : rays) {
      ray.view = static_cast<int>(rng.Below(static_cast<uint32_t>(views.size())));
      ray.u = rng.Uniform() * static_cast<float>(views.cameras[ray.view].width);
      ray.v = rng.Uniform() * static_cast<float>(views.cameras[ray.view].height);
      ray.jitter = rng.Uniform();
    }
    return rays;
  }
  const std::vector<std::pair<int, uint32_t>> pixels = RayPixels(views, *options.ray_masks);
  if (pixels.empty()) return {};
  for (Ray& ray : rays) {
    const auto [view, index] = pixels[rng.Below(static_cast<uint32_t>(pixels.size()))];
    const uint32_t width = static_cast<uint32_t>(views.cameras[view].width);
    ray.view = view;
    ray.u = static_cast<float>(index % width) + rng.Uniform();
    ray.v = static_cast<float>(index / width) + rng.Uniform();
    ray.jitter = rng.Uniform();
  }
  return rays;
}

}  // namespace

Status PhotoConsistentPoints(const TrainingViews& views, const PhotoConsistencyOptions& options,
                             PointCloud* points) {
  M4D_RETURN_IF_ERROR(CheckOptions(views, options));
  const float extent = CameraSceneBounds(views.cameras).extent;
  if (!(extent > 0)) return Status(M4D_ERR_INVALID_ARG, "photo-consistent points: zero extent");
  // The other views that must see a point (the ray's own view sees it by construction).
  const int min_views = std::max(1, std::min(options.min_views, views.size() / 2) - 1);
  const std::vector<Ray> rays = DrawRays(views, options);
  std::vector<Found> found(rays.size());
  ThreadPool pool(options.threads);
  std::vector<std::vector<float>> scratch(static_cast<size_t>(pool.size()));
  ParallelForChunks(&pool, rays.size(), 256, [&](size_t begin, size_t end, int worker) {
    for (size_t i = begin; i < end; ++i) {
      const float far =
          std::max(2.0f * views.cameras[rays[i].view].near_plane, options.far_extents * extent);
      found[i] = SweepRay(views, rays[i], far, min_views, options, &scratch[worker]);
    }
  });
  *points = PointCloud();
  for (const Found& f : found) {
    if (!f.ok || points->size() == options.points) continue;
    points->positions.insert(points->positions.end(), f.position, f.position + 3);
    for (float colour : f.colour) points->colors.push_back(std::clamp(colour, 0.0f, 1.0f));
  }
  return Status::Ok();
}

}  // namespace m4d
