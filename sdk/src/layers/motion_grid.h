// MotionGrid: the decoded multi-resolution motion grid of one frame (bitstream-spec 4.4),
// and its reader. Values stay quantized (int16); the step is applied after interpolation.
#ifndef M4D_SDK_LAYERS_MOTION_GRID_H_
#define M4D_SDK_LAYERS_MOTION_GRID_H_

#include <cstddef>
#include <cstdint>

#include "sdk/src/common/byte_reader.h"
#include "sdk/src/common/hooked_allocator.h"
#include "sdk/src/common/status.h"
#include "sdk/src/entropy/symbol_block_reader.h"
#include "sdk/src/layers/motion_config.h"

namespace m4d {

struct MotionGrid {
  MotionGrid() = default;
  explicit MotionGrid(const M4dAllocator* hooks) {
    for (auto& v : values) v = Buffer<int16_t>(HookedAllocator<int16_t>(hooks));
    for (auto& f : nonzero_bricks) f = Buffer<int32_t>(HookedAllocator<int32_t>(hooks));
    for (auto& a : active_voxels) a = Buffer<uint32_t>(HookedAllocator<uint32_t>(hooks));
    active_bitmap = Buffer<uint64_t>(HookedAllocator<uint64_t>(hooks));
  }
  float box_min[3] = {0, 0, 0};
  float box_scale[3] = {1, 1, 1};
  float step[kMaxGridLevels] = {0, 0, 0, 0};
  // values[l] holds G_l[z][y][x][c], R_l^3 * C_l entries, x fastest then channels innermost:
  // index ((z * R + y) * R + x) * C + c.
  Buffer<int16_t> values[kMaxGridLevels];
  // Reader state, not stream data: the brick flags values[l] was last read with (bricks
  // outside them are zero). Empty when unknown; code that writes values directly clears it.
  Buffer<int32_t> nonzero_bricks[kMaxGridLevels];
  // Reader state of the active-voxel syntax (0.10): the voxels values[l] was last read at
  // (every other voxel is zero), valid while active_valid[l]; and a scratch bitmap.
  Buffer<uint32_t> active_voxels[kMaxGridLevels];
  bool active_valid[kMaxGridLevels] = {false, false, false, false};
  Buffer<uint64_t> active_bitmap;
};

// Reads a MOTION_GRID payload of the brick syntax (versions 0.2 to 0.9) into *grid (resizing
// its level buffers to the configuration).
Status ReadMotionGrid(ByteReader* reader, RansLayout layout, const GridConfig& config,
                      MotionGrid* grid);

// Reads a MOTION_GRID payload of the active-voxel syntax (0.10 on): each level codes the
// values of the voxels that the `count` Gaussians at `positions` (3 per Gaussian; the dynamic
// set the grid moves) read, and every other voxel is zero.
Status ReadActiveMotionGrid(ByteReader* reader, RansLayout layout, const GridConfig& config,
                            const float* positions, size_t count, MotionGrid* grid);

}  // namespace m4d

#endif  // M4D_SDK_LAYERS_MOTION_GRID_H_
