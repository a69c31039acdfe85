#include "layers/motion_grid.h"

#include <algorithm>
#include <cstddef>
#include <cstring>
#include <string>

#include "common/spec_limits.h"
#include "entropy/symbol_block_reader.h"

namespace m4d {
namespace {

// Voxels of brick b along an axis of r voxels: kBrickSize, fewer for a partial last brick.
int BrickExtent(int b, int r) { return std::min(kBrickSize, r - b * kBrickSize); }

// Reads level(l) (spec 4.4). `flags` and `coded` are scratch buffers kept across levels.
Status ReadLevel(ByteReader* reader, int l, int r, int c, Buffer<int32_t>* flags,
                 Buffer<int32_t>* coded, float* step, Buffer<int16_t>* values) {
  auto error = [l](const Status& status, const char* what) {
    return Status(status.code(), "grid level " + std::to_string(l) + what + status.message());
  };
  if (!reader->ReadFiniteF32(step)) return error(BitstreamError(""), ": bad or missing step");

  const int n = (r + kBrickSize - 1) / kBrickSize;
  const uint32_t num_bricks = static_cast<uint32_t>(n) * n * n;
  flags->resize(num_bricks);
  Status status = ReadSymbolBlock(reader, num_bricks, 0, 1, flags->data());
  if (!status.ok()) return error(status, " brick flags: ");

  // V_l: bounded by R_l^3 * C_l, which the sequence header limits.
  uint64_t voxels = 0;
  const int32_t* flag = flags->data();
  for (int bz = 0; bz < n; ++bz) {
    for (int by = 0; by < n; ++by) {
      for (int bx = 0; bx < n; ++bx) {
        if (*flag++) voxels += BrickExtent(bz, r) * BrickExtent(by, r) * BrickExtent(bx, r);
      }
    }
  }
  const uint32_t count = static_cast<uint32_t>(voxels * static_cast<uint64_t>(c));
  coded->resize(count);
  status = ReadSymbolBlock(reader, count, -32768, 32767, coded->data());
  if (!status.ok()) return error(status, " values: ");

  // Unflagged bricks are zero; each row of a flagged brick is contiguous in both the coded
  // order and the dense layout, so the scatter is a narrowing copy per row.
  const size_t rs = static_cast<size_t>(r);
  values->resize(rs * rs * rs * static_cast<size_t>(c));
  int16_t* dense = values->data();
  std::memset(dense, 0, values->size() * sizeof(int16_t));  // assign() does not become memset
  const int32_t* src = coded->data();
  flag = flags->data();
  for (int bz = 0; bz < n; ++bz) {
    for (int by = 0; by < n; ++by) {
      for (int bx = 0; bx < n; ++bx) {
        if (!*flag++) continue;
        const int z0 = bz * kBrickSize, y0 = by * kBrickSize, x0 = bx * kBrickSize;
        const int z1 = z0 + BrickExtent(bz, r), y1 = y0 + BrickExtent(by, r);
        const size_t row = static_cast<size_t>(BrickExtent(bx, r)) * c;
        for (int z = z0; z < z1; ++z) {
          for (int y = y0; y < y1; ++y) {
            int16_t* dst = dense + ((z * rs + y) * rs + x0) * c;
            for (size_t i = 0; i < row; ++i) dst[i] = static_cast<int16_t>(src[i]);
            src += row;
          }
        }
      }
    }
  }
  return Status::Ok();
}

}  // namespace

Status ReadMotionGrid(ByteReader* reader, const GridConfig& config, MotionGrid* grid) {
  for (int a = 0; a < 3; ++a) {
    if (!reader->ReadFiniteF32(&grid->box_min[a])) {
      return BitstreamError("grid: bad or missing box_min");
    }
  }
  for (int a = 0; a < 3; ++a) {
    if (!reader->ReadFiniteF32(&grid->box_scale[a]) || !(grid->box_scale[a] > 0)) {
      return BitstreamError("grid: box_scale missing, not finite or not positive");
    }
  }
  const HookedAllocator<int32_t> alloc(grid->values[0].get_allocator());
  Buffer<int32_t> flags(alloc);
  Buffer<int32_t> coded(alloc);
  for (int l = 0; l < config.num_levels; ++l) {
    M4D_RETURN_IF_ERROR(ReadLevel(reader, l, config.resolution[l], config.channels[l], &flags,
                                  &coded, &grid->step[l], &grid->values[l]));
  }
  // Levels the configuration no longer has give their memory back.
  for (int l = config.num_levels; l < kMaxGridLevels; ++l) {
    grid->values[l] = Buffer<int16_t>(grid->values[l].get_allocator());
  }
  return Status::Ok();
}

}  // namespace m4d
