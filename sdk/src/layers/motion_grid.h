// MotionGrid: the decoded multi-resolution motion grid of one frame (bitstream-spec 4.4),
// and its reader. Values stay quantized (int16); the step is applied after interpolation.
#ifndef M4D_SDK_LAYERS_MOTION_GRID_H_
#define M4D_SDK_LAYERS_MOTION_GRID_H_

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
};

// Reads a MOTION_GRID payload into *grid (resizing its level buffers to the configuration).
Status ReadMotionGrid(ByteReader* reader, RansLayout layout, const GridConfig& config,
                      MotionGrid* grid);

}  // namespace m4d

#endif  // M4D_SDK_LAYERS_MOTION_GRID_H_
