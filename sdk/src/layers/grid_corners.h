// Where a Gaussian reads the motion grid (bitstream-spec 6.3 steps 1 and 2), with the spec's
// float operations, and the active voxels of a level: those some Gaussian of the moved set
// reads. From version 0.10 a MOTION_GRID codes the active voxels' values only (spec 4.4), so the
// decoder derives them from the set it is about to move, as the encoder did.
#ifndef M4D_SDK_LAYERS_GRID_CORNERS_H_
#define M4D_SDK_LAYERS_GRID_CORNERS_H_

#include <algorithm>
#include <cstddef>
#include <cstdint>

namespace m4d {

// Spec 6.3 step 1: the box coordinates u of position p, or false when p is outside the box
// (or NaN) and the Gaussian is left unchanged.
inline bool GridBoxCoordinates(const float box_min[3], const float box_scale[3], const float* p,
                               float u[3]) {
  for (int a = 0; a < 3; ++a) {
    u[a] = (p[a] - box_min[a]) * box_scale[a];
    if (!(u[a] >= 0.0f && u[a] <= 1.0f)) return false;
  }
  return true;
}

// Spec 6.3 step 2 for one level of `resolution` voxels per axis: the dense indices
// (z * R + y) * R + x of the 8 corners (k = dx + 2 dy + 4 dz) and their trilinear weights.
inline void GridLevelCorners(const float u[3], int resolution, uint32_t dense[8], float w[8]) {
  int i[3];
  float w0[3], w1[3];
  for (int a = 0; a < 3; ++a) {
    const float g = u[a] * static_cast<float>(resolution - 1);
    i[a] = std::min(static_cast<int>(g), resolution - 2);
    const float t = g - static_cast<float>(i[a]);
    w0[a] = 1.0f - t;
    w1[a] = t;
  }
  const uint32_t r = static_cast<uint32_t>(resolution);
  for (int k = 0; k < 8; ++k) {
    const int dx = k & 1, dy = (k >> 1) & 1, dz = (k >> 2) & 1;
    w[k] = ((dx ? w1[0] : w0[0]) * (dy ? w1[1] : w0[1])) * (dz ? w1[2] : w0[2]);
    dense[k] = (static_cast<uint32_t>(i[2] + dz) * r + static_cast<uint32_t>(i[1] + dy)) * r +
               static_cast<uint32_t>(i[0] + dx);
  }
}

// Words of a bitmap with one bit per voxel of a level of `resolution` voxels per axis.
inline size_t ActiveVoxelWords(int resolution) {
  const size_t r = static_cast<size_t>(resolution);
  return (r * r * r + 63) / 64;
}

// Sets in `bitmap` (ActiveVoxelWords words, zeroed by the caller) the bit of every corner that
// a Gaussian of `count` at `positions` (3 per Gaussian) inside the box reads at this level.
inline void MarkActiveVoxels(const float box_min[3], const float box_scale[3], int resolution,
                             const float* positions, size_t count, uint64_t* bitmap) {
  for (size_t i = 0; i < count; ++i) {
    float u[3], w[8];
    uint32_t dense[8];
    if (!GridBoxCoordinates(box_min, box_scale, positions + 3 * i, u)) continue;
    GridLevelCorners(u, resolution, dense, w);
    for (uint32_t d : dense) bitmap[d >> 6] |= uint64_t{1} << (d & 63);
  }
}

// The set bits of `bitmap` (`words` words) as ascending voxel indices appended to *out.
template <class Vector>
void AppendActiveVoxels(const uint64_t* bitmap, size_t words, Vector* out) {
  for (size_t w = 0; w < words; ++w) {
    for (uint64_t bits = bitmap[w]; bits != 0; bits &= bits - 1) {
      out->push_back(static_cast<uint32_t>(w * 64 + static_cast<size_t>(__builtin_ctzll(bits))));
    }
  }
}

}  // namespace m4d

#endif  // M4D_SDK_LAYERS_GRID_CORNERS_H_
