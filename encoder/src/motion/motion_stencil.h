// MotionStencil: where each dynamic Gaussian reads the motion grid (bitstream-spec 6.3 steps 1
// and 2) while its position is fixed, as it is while one frame's motion is trained: per level
// the 8 corner voxels and their trilinear weights, computed with the spec's float operations so
// that training reads exactly the features a decoder computes. Only voxels some Gaussian reads
// (the active voxels) are trainable; every other voxel stays zero, which is also what the
// rate term prefers.
#ifndef M4D_ENCODER_MOTION_MOTION_STENCIL_H_
#define M4D_ENCODER_MOTION_MOTION_STENCIL_H_

#include <cstddef>
#include <cstdint>
#include <vector>

#include "sdk/src/layers/motion_config.h"

namespace m4d {

struct GridBox {
  float min[3] = {0, 0, 0};
  float scale[3] = {1, 1, 1};  // 1 / extent per axis
};

struct MotionStencil {
  size_t gaussian_count = 0;
  int num_levels = 0;
  // Per Gaussian: 1 when inside the box (moved), 0 when the decoder leaves it unchanged.
  std::vector<uint8_t> inside;
  // Per level: for each Gaussian 8 corners (k = dx + 2 dy + 4 dz), each an index into that
  // level's active voxels, and the matching weights. Outside Gaussians get weight 0, index 0.
  std::vector<uint32_t> corner[kMaxGridLevels];
  std::vector<float> weight[kMaxGridLevels];
  // Per level: the dense voxel index (z * R + y) * R + x of each active voxel, ascending.
  std::vector<uint32_t> active[kMaxGridLevels];
};

// Builds the stencil of `count` Gaussians at `positions` (3 per Gaussian).
void BuildMotionStencil(const GridConfig& config, const GridBox& box, const float* positions,
                        size_t count, MotionStencil* stencil);

}  // namespace m4d

#endif  // M4D_ENCODER_MOTION_MOTION_STENCIL_H_
