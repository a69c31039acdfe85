#include "encoder/src/motion/motion_stencil.h"

#include <algorithm>

#include "sdk/src/layers/grid_corners.h"

namespace m4d {

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
      if (!GridBoxCoordinates(box.min, box.scale, positions + 3 * i, u)) continue;
      stencil->inside[i] = 1;
      GridLevelCorners(u, config.resolution[l], &corner[8 * i], &weight[8 * i]);
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
