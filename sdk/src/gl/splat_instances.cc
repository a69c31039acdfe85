#include "sdk/src/gl/splat_instances.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>

#include "sdk/src/render/projection_constants.h"
#include "sdk/src/render/radix_sort.h"
#include "sdk/src/render/splat_projection.h"

namespace m4d {
namespace {

constexpr size_t kChunk = 1024;  // Gaussians per task

using Clock = std::chrono::steady_clock;

double MillisecondsSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// The axes of the ellipse d^T conic d <= k^2 (see SplatInstance).
void EllipseAxes(float a, float b, float c, float opacity, SplatInstance* s) {
  const float inv_det = 1.0f / (a * c - b * b);  // covariance = conic^-1
  const float xx = c * inv_det, xy = -b * inv_det, yy = a * inv_det;
  const float mid = 0.5f * (xx + yy);
  const float disc = std::sqrt(std::max(0.0f, mid * mid - (xx * yy - xy * xy)));
  const float major = mid + disc, minor = std::max(mid - disc, 1e-12f);
  float ex = xy, ey = major - xx;  // eigenvector of the major eigenvalue
  float len = std::sqrt(ex * ex + ey * ey);
  if (!(len > 1e-12f * major)) {
    ex = xx >= yy ? 1.0f : 0.0f;
    ey = 1.0f - ex;
    len = 1.0f;
  }
  s->k = std::sqrt(std::max(0.0f, 2.0f * std::log(255.0f * opacity) + 0.05f));
  const float h = s->k * std::sqrt(major) / len;
  s->axis[0] = ex * h;
  s->axis[1] = ey * h;
  s->minor = s->k * std::sqrt(minor);
}

uint32_t DepthKey(float depth) {
  uint32_t key;
  std::memcpy(&key, &depth, sizeof(key));  // depth > near plane > 0: bits sort like floats
  return key;
}

}  // namespace

Status SplatInstanceBuilder::Build(const Camera& camera, const M4dGaussians* layers,
                                   int layer_count, int sh_degree,
                                   std::vector<SplatInstance>* instances,
                                   SplatInstanceTimings* timings) {
  M4D_RETURN_IF_ERROR(ValidateCamera(camera));
  if (sh_degree < 0 || sh_degree > 3) {
    return Status(M4D_ERR_INVALID_ARG, "renderer: SH degree must be 0..3");
  }
  Clock::time_point start = Clock::now();
  size_t total = 0;
  for (int l = 0; l < layer_count; ++l) total += layers[l].count;
  projected_.Resize(total);
  const ProjectionConstants pc = MakeProjectionConstants(camera);
  ParallelForChunks(&pool_, total, kChunk, [&](size_t begin, size_t end, int) {
    size_t offset = 0;
    for (int l = 0; l < layer_count; ++l) {
      const size_t lo = std::max(begin, offset), hi = std::min(end, offset + layers[l].count);
      if (lo < hi)
        ProjectSplats(pc, layers[l], sh_degree, lo - offset, hi - offset, offset, &projected_);
      offset += layers[l].count;
    }
  });
  keys_.clear();
  order_.clear();
  for (size_t i = 0; i < total; ++i) {
    if (projected_.radius[i] == 0.0f) continue;
    keys_.push_back(DepthKey(projected_.depth[i]));
    order_.push_back(static_cast<uint32_t>(i));
  }
  timings->project_ms = MillisecondsSince(start);

  start = Clock::now();
  RadixSortPairs(&keys_, &order_, &key_scratch_, &order_scratch_);
  instances->resize(order_.size());
  ParallelForChunks(&pool_, order_.size(), kChunk, [&](size_t begin, size_t end, int) {
    for (size_t k = begin; k < end; ++k) {
      const size_t i = order_[k];
      SplatInstance& s = (*instances)[k];
      s.mean[0] = projected_.mean_x[i];
      s.mean[1] = projected_.mean_y[i];
      s.extent[0] = projected_.extent_x[i];
      s.extent[1] = projected_.extent_y[i];
      s.opacity = projected_.opacity[i];
      EllipseAxes(projected_.conic_a[i], projected_.conic_b[i], projected_.conic_c[i], s.opacity,
                  &s);
      for (int c = 0; c < 3; ++c) s.color[c] = projected_.color[c][i];
    }
  });
  timings->sort_ms = MillisecondsSince(start);
  return Status::Ok();
}

}  // namespace m4d
