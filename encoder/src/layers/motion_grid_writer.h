// Encoding of MOTION_GRID (bitstream-spec 4.4): quantization of a float grid
// (Q(M) = floor(M / step + 0.5), paper section 5.1) and its two syntaxes: brick flags and the
// flagged bricks' values (0.2 to 0.9), or the values of the active voxels (0.10 on).
#ifndef M4D_ENCODER_LAYERS_MOTION_GRID_WRITER_H_
#define M4D_ENCODER_LAYERS_MOTION_GRID_WRITER_H_

#include <cstddef>
#include <vector>

#include "sdk/src/common/byte_writer.h"
#include "sdk/src/common/status.h"
#include "sdk/src/entropy/symbol_block_reader.h"
#include "sdk/src/layers/motion_config.h"

namespace m4d {

// A float motion grid as the encoder trains it; same layout as MotionGrid.values.
struct FloatMotionGrid {
  float box_min[3] = {0, 0, 0};
  float box_scale[3] = {1, 1, 1};
  float step[kMaxGridLevels] = {1.f / 64, 1.f / 64, 1.f / 64, 1.f / 64};
  std::vector<float> values[kMaxGridLevels];  // [z][y][x][c]
};

// Quantizes and writes a MOTION_GRID payload of the brick syntax. Quantized values are clamped
// to the range the alphabet limit allows around zero (+-2047); box_scale must be positive and
// finite.
Status WriteMotionGrid(const GridConfig& config, const FloatMotionGrid& grid, RansLayout layout,
                       ByteWriter* out);

// The same in the active-voxel syntax, for the dynamic set of `count` Gaussians at `positions`
// (3 per Gaussian) that the grid moves: only the voxels they read are coded, the rest dropped.
Status WriteActiveMotionGrid(const GridConfig& config, const FloatMotionGrid& grid,
                             const float* positions, size_t count, RansLayout layout,
                             ByteWriter* out);

}  // namespace m4d

#endif  // M4D_ENCODER_LAYERS_MOTION_GRID_WRITER_H_
