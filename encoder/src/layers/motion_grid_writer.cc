#include "encoder/src/layers/motion_grid_writer.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

#include "encoder/src/entropy/symbol_block_writer.h"
#include "sdk/src/layers/grid_corners.h"

namespace m4d {
namespace {

// Largest quantized magnitude: keeps every values block within the 4096-symbol alphabet.
constexpr float kMaxQuantized = 2047.0f;

Status InvalidArg(const std::string& message) {
  return Status(M4D_ERR_INVALID_ARG, "motion grid: " + message);
}

bool FinitePositive(float v) { return std::isfinite(v) && v > 0; }

Status CheckInputs(const GridConfig& config, const FloatMotionGrid& grid) {
  if (config.num_levels < 1 || config.num_levels > kMaxGridLevels) {
    return InvalidArg("level count out of range 1..4");
  }
  for (int a = 0; a < 3; ++a) {
    if (!std::isfinite(grid.box_min[a])) return InvalidArg("box_min not finite");
    if (!FinitePositive(grid.box_scale[a])) return InvalidArg("box_scale not finite and > 0");
  }
  for (int l = 0; l < config.num_levels; ++l) {
    const std::string level = "level " + std::to_string(l);
    if (config.resolution[l] < 2 || config.resolution[l] > kMaxGridResolution ||
        config.channels[l] < 1 || config.channels[l] > kMaxGridChannels) {
      return InvalidArg(level + ": resolution or channels out of range");
    }
    if (!FinitePositive(grid.step[l])) return InvalidArg(level + ": step not finite and > 0");
    if (grid.values[l].size() != config.level_values(l)) {
      return InvalidArg(level + ": " + std::to_string(grid.values[l].size()) +
                        " values, the configuration needs " +
                        std::to_string(config.level_values(l)));
    }
  }
  return Status::Ok();
}

// Q(M) = floor(M / step + 0.5), clamped.
Status Quantize(const std::vector<float>& values, float step, std::vector<int32_t>* out) {
  out->resize(values.size());
  for (size_t i = 0; i < values.size(); ++i) {
    if (!std::isfinite(values[i])) return InvalidArg("value not finite");
    const float q = std::floor(values[i] / step + 0.5f);
    (*out)[i] = static_cast<int32_t>(std::min(std::max(q, -kMaxQuantized), kMaxQuantized));
  }
  return Status::Ok();
}

Status WriteLevel(int r, int c, float step, const std::vector<int32_t>& q, RansLayout layout,
                  ByteWriter* out) {
  const int n = (r + kBrickSize - 1) / kBrickSize;
  std::vector<int32_t> flags(static_cast<size_t>(n) * n * n, 0);
  std::vector<int32_t> coded;
  const size_t rs = static_cast<size_t>(r);
  size_t brick = 0;
  for (int bz = 0; bz < n; ++bz) {
    for (int by = 0; by < n; ++by) {
      for (int bx = 0; bx < n; ++bx, ++brick) {
        const int z0 = bz * kBrickSize, y0 = by * kBrickSize, x0 = bx * kBrickSize;
        const int z1 = std::min(z0 + kBrickSize, r), y1 = std::min(y0 + kBrickSize, r);
        const size_t row = static_cast<size_t>(std::min(x0 + kBrickSize, r) - x0) * c;
        const size_t start = coded.size();
        bool any = false;
        for (int z = z0; z < z1; ++z) {
          for (int y = y0; y < y1; ++y) {
            const int32_t* src = q.data() + ((z * rs + y) * rs + x0) * c;
            for (size_t i = 0; i < row; ++i) any = any || src[i] != 0;
            coded.insert(coded.end(), src, src + row);
          }
        }
        flags[brick] = any ? 1 : 0;
        if (!any) coded.resize(start);
      }
    }
  }
  out->WriteF32(step);
  M4D_RETURN_IF_ERROR(WriteSymbolBlock(flags.data(), flags.size(), layout, out));
  return WriteSymbolBlock(coded.data(), coded.size(), layout, out);
}

// Writes level l of the active-voxel syntax: the step, then the values of the voxels the
// Gaussians at `positions` read, ascending, channels consecutive. The values elsewhere are
// dropped: no Gaussian reads them, so they do not change the decoded frame.
Status WriteActiveLevel(int r, int c, float step, const std::vector<int32_t>& q,
                        const FloatMotionGrid& grid, const float* positions, size_t count,
                        RansLayout layout, ByteWriter* out) {
  std::vector<uint64_t> bitmap(ActiveVoxelWords(r), 0);
  MarkActiveVoxels(grid.box_min, grid.box_scale, r, positions, count, bitmap.data());
  std::vector<uint32_t> active;
  AppendActiveVoxels(bitmap.data(), bitmap.size(), &active);
  std::vector<int32_t> coded;
  coded.reserve(active.size() * static_cast<size_t>(c));
  for (uint32_t v : active) {
    const int32_t* src = &q[static_cast<size_t>(v) * c];
    coded.insert(coded.end(), src, src + c);
  }
  out->WriteF32(step);
  return WriteSymbolBlock(coded.data(), coded.size(), layout, out);
}

// Checks the inputs and quantizes every level, so that a bad value leaves `out` untouched.
Status QuantizeGrid(const GridConfig& config, const FloatMotionGrid& grid,
                    std::vector<int32_t> q[kMaxGridLevels]) {
  M4D_RETURN_IF_ERROR(CheckInputs(config, grid));
  for (int l = 0; l < config.num_levels; ++l) {
    M4D_RETURN_IF_ERROR(Quantize(grid.values[l], grid.step[l], &q[l]));
  }
  return Status::Ok();
}

void WriteBox(const FloatMotionGrid& grid, ByteWriter* out) {
  for (int a = 0; a < 3; ++a) out->WriteF32(grid.box_min[a]);
  for (int a = 0; a < 3; ++a) out->WriteF32(grid.box_scale[a]);
}

}  // namespace

Status WriteMotionGrid(const GridConfig& config, const FloatMotionGrid& grid, RansLayout layout,
                       ByteWriter* out) {
  std::vector<int32_t> q[kMaxGridLevels];
  M4D_RETURN_IF_ERROR(QuantizeGrid(config, grid, q));
  WriteBox(grid, out);
  for (int l = 0; l < config.num_levels; ++l) {
    M4D_RETURN_IF_ERROR(
        WriteLevel(config.resolution[l], config.channels[l], grid.step[l], q[l], layout, out));
  }
  return Status::Ok();
}

Status WriteActiveMotionGrid(const GridConfig& config, const FloatMotionGrid& grid,
                             const float* positions, size_t count, RansLayout layout,
                             ByteWriter* out) {
  std::vector<int32_t> q[kMaxGridLevels];
  M4D_RETURN_IF_ERROR(QuantizeGrid(config, grid, q));
  WriteBox(grid, out);
  for (int l = 0; l < config.num_levels; ++l) {
    M4D_RETURN_IF_ERROR(WriteActiveLevel(config.resolution[l], config.channels[l], grid.step[l],
                                         q[l], grid, positions, count, layout, out));
  }
  return Status::Ok();
}

}  // namespace m4d
