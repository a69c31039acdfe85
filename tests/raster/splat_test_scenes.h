// Small random scenes and cameras for the rasterizer tests.
#ifndef M4D_TESTS_RASTER_SPLAT_TEST_SCENES_H_
#define M4D_TESTS_RASTER_SPLAT_TEST_SCENES_H_

#include <cmath>
#include <cstddef>
#include <random>
#include <vector>

#include "sdk/src/layers/gaussian_set.h"
#include "sdk/src/layers/gaussian_views.h"
#include "sdk/src/render/camera.h"

namespace m4d {
namespace test {

// A camera at `eye` looking at `target` (OpenCV axes, world y down), principal point shifted
// off the image centre by (dx, dy) pixels.
inline Camera LookAtCamera(int width, int height, float focal, float dx, float dy,
                           const float eye[3], const float target[3]) {
  Camera camera;
  camera.width = width;
  camera.height = height;
  camera.fx = focal;
  camera.fy = focal * 1.05f;
  camera.cx = 0.5f * width + dx;
  camera.cy = 0.5f * height + dy;
  double f[3], len = 0;
  for (int a = 0; a < 3; ++a) {
    f[a] = target[a] - eye[a];
    len += f[a] * f[a];
  }
  for (double& v : f) v /= std::sqrt(len);
  // right = down x forward with world "down" = +y; then down = forward x right.
  const double down[3] = {0, 1, 0};
  double right[3] = {down[1] * f[2] - down[2] * f[1], down[2] * f[0] - down[0] * f[2],
                     down[0] * f[1] - down[1] * f[0]};
  len = std::sqrt(right[0] * right[0] + right[1] * right[1] + right[2] * right[2]);
  for (double& v : right) v /= len;
  const double d[3] = {f[1] * right[2] - f[2] * right[1], f[2] * right[0] - f[0] * right[2],
                       f[0] * right[1] - f[1] * right[0]};
  const double* rows[3] = {right, d, f};
  for (int r = 0; r < 3; ++r) {
    camera.translation[r] = 0;
    for (int k = 0; k < 3; ++k) {
      camera.rotation[3 * r + k] = static_cast<float>(rows[r][k]);
      camera.translation[r] -= static_cast<float>(rows[r][k] * eye[k]);
    }
  }
  return camera;
}

// The default test camera: slightly rotated, principal point off-centre.
inline Camera TestCamera(int width, int height) {
  const float eye[3] = {0.3f, -0.2f, -4.0f};
  const float target[3] = {0.0f, 0.1f, 0.0f};
  return LookAtCamera(width, height, 1.1f * width, 0.13f * width, -0.11f * height, eye, target);
}

struct SceneOptions {
  size_t count = 20;
  int sh_degree = 3;
  float extent = 1.0f;         // positions in [-extent, extent]^3 around the origin
  float log_scale_lo = -2.6f;  // log-uniform scales
  float log_scale_hi = -1.6f;
  float logit_lo = -1.0f, logit_hi = 1.2f;
  float sh_dc = 1.0f, sh_rest = 0.3f;  // uniform amplitudes
};

inline GaussianSet RandomGaussians(const SceneOptions& o, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  auto uniform = [&](float lo, float hi) { return lo + (hi - lo) * 0.5f * (unit(rng) + 1.0f); };
  GaussianSet set;
  set.sh_degree = o.sh_degree;
  set.Resize(o.count);
  const int k = ShCoefficients(o.sh_degree);
  for (size_t i = 0; i < o.count; ++i) {
    for (int a = 0; a < 3; ++a) {
      set.positions[3 * i + a] = o.extent * unit(rng);
      set.log_scales[3 * i + a] = uniform(o.log_scale_lo, o.log_scale_hi);
    }
    for (int c = 0; c < 4; ++c) set.rotations[4 * i + c] = unit(rng) + (c == 0 ? 1.5f : 0.0f);
    set.opacity_logits[i] = uniform(o.logit_lo, o.logit_hi);
    for (int j = 0; j < 3 * k; ++j) {
      set.sh[static_cast<size_t>(3 * k) * i + j] = (j < 3 ? o.sh_dc : o.sh_rest) * unit(rng);
    }
  }
  return set;
}

inline std::vector<M4dGaussians> Views(const std::vector<GaussianSet>& sets) {
  std::vector<M4dGaussians> views;
  for (const GaussianSet& s : sets) views.push_back(GaussianView(s));
  return views;
}

}  // namespace test
}  // namespace m4d

#endif  // M4D_TESTS_RASTER_SPLAT_TEST_SCENES_H_
