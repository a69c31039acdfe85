#include "encoder/src/motion/motion_stencil.h"

#include <algorithm>
#include <cmath>

namespace m4d {
namespace {

// Spec 6.3 step 1: box coordinates, or false when the Gaussian is outside (or NaN).
bool BoxCoordinates(const GridBox& box, const float* p, float u[3]) {
  for (int a = 0; a < 3; ++a) {
    u[a] = (p[a] - box.min[a]) * box.scale[a];
    if (!(u[a] >= 0.0f && u[a] <= 1.0f)) return false;
  }
  return true;
}

// Spec 6.3 step 2 for one level: dense corner indices and weights.
void LevelCorners(const float u[3], int resolution, uint32_t dense[8], float w[8]) {
  int i[3];
  float w0[3], w1[3];
  for (int a = 0; a < 3; ++a) {
    float g = u[a] * static_cast<float>(resolution - 1);
    i[a] = std::min(static_cast<int>(g), resolution - 2);
    float t = g - static_cast<float>(i[a]);
    w0[a] = 1.0f - t;
    w1[a] = t;
  }
  const uint32_t r = static_cast<uint32_t>(resolution);
  for (int k = 0; k < 8; ++k) {
    int dx = k & 1, dy = (k >> 1) & 1, dz = (k >> 2) & 1;
    w[k] = ((dx ? w1[0] : w0[0]) * (dy ? w1[1] : w0[1])) * (dz ? w1[2] : w0[2]);
    dense[k] = ((static_cast<uint32_t>(i[2] + dz) * r + static_cast<uint32_t>(i[1] + dy)) * r +
                static_cast<uint32_t>(i[0] + dx));
  }
}

}  // namespace

void BuildMotionStencil(const GridConfig& config, const GridBox& box, const float* positions,
                        size_t count, MotionStencil* stencil) {
  stencil->gaussian_count = count;
  stencil->num_levels = config.num_levels;
  stencil->inside.assign(count, 0);
  for (int l = 0; l < config.num_levels; ++l) {
    std::vector<uint32_t>& corner = stencil->corner[l];
    std::vector<float>& weight = stencil->weight[l];
    corner.assign(8 * count, 0);
    weight.assign(8 * count, 0.0f);
    for (size_t i = 0; i < count; ++i) {
      float u[3];
      if (!BoxCoordinates(box, positions + 3 * i, u)) continue;
      stencil->inside[i] = 1;
      LevelCorners(u, config.resolution[l], &corner[8 * i], &weight[8 * i]);
    }
    // Dense indices to active-voxel indices: sort the distinct voxels some Gaussian reads.
    std::vector<uint32_t>& active = stencil->active[l];
    active.clear();
    for (size_t i = 0; i < count; ++i) {
      if (stencil->inside[i]) active.insert(active.end(), &corner[8 * i], &corner[8 * i + 8]);
    }
    std::sort(active.begin(), active.end());
    active.erase(std::unique(active.begin(), active.end()), active.end());
    for (size_t i = 0; i < count; ++i) {
      if (!stencil->inside[i]) continue;
      for (int k = 0; k < 8; ++k) {
        uint32_t& c = corner[8 * i + k];
        c = static_cast<uint32_t>(std::lower_bound(active.begin(), active.end(), c) -
                                  active.begin());
      }
    }
  }
  for (int l = config.num_levels; l < kMaxGridLevels; ++l) {
    stencil->corner[l].clear();
    stencil->weight[l].clear();
    stencil->active[l].clear();
  }
}

}  // namespace m4d
