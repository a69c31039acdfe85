#include "sdk/src/layers/motion_grid.h"

#include <algorithm>
#include <cstddef>
#include <cstring>
#include <string>

#include "sdk/src/common/spec_limits.h"
#include "sdk/src/entropy/symbol_block_reader.h"
#include "sdk/src/layers/grid_corners.h"

namespace m4d {
namespace {

// Voxels of brick b along an axis of r voxels: kBrickSize, fewer for a partial last brick.
int BrickExtent(int b, int r) { return std::min(kBrickSize, r - b * kBrickSize); }

// The voxel box of brick (bx, by, bz): [x0, x1) x [y0, y1) x [z0, z1).
struct BrickBox {
  int x0, x1, y0, y1, z0, z1;
};
BrickBox BrickAt(int bx, int by, int bz, int r) {
  const int x0 = bx * kBrickSize, y0 = by * kBrickSize, z0 = bz * kBrickSize;
  return {x0, x0 + BrickExtent(bx, r), y0, y0 + BrickExtent(by, r), z0, z0 + BrickExtent(bz, r)};
}

// Each row of a brick is contiguous in the dense layout (and in the coded order).
// Writes the brick's rows from `src` (narrowing), or zeros when src is null; returns the end of
// what it read.
const int32_t* FillBrick(const BrickBox& box, int r, int c, const int32_t* src, int16_t* dense) {
  const size_t rs = static_cast<size_t>(r);
  const size_t row = static_cast<size_t>(box.x1 - box.x0) * c;
  for (int z = box.z0; z < box.z1; ++z) {
    for (int y = box.y0; y < box.y1; ++y) {
      int16_t* dst = dense + ((z * rs + y) * rs + box.x0) * c;
      if (src == nullptr) {
        std::memset(dst, 0, row * sizeof(int16_t));
        continue;
      }
      for (size_t i = 0; i < row; ++i) dst[i] = static_cast<int16_t>(src[i]);
      src += row;
    }
  }
  return src;
}

// Reads level(l) (spec 4.4). `flags` and `coded` are scratch buffers kept across levels;
// `nonzero` holds the flags of the level's previous frame, so only the bricks that were
// coded then and are not now need zeroing (mostly-zero grids stay cheap to decode).
Status ReadLevel(ByteReader* reader, RansLayout layout, int l, int r, int c, Buffer<int32_t>* flags,
                 Buffer<int32_t>* coded, float* step, Buffer<int16_t>* values,
                 Buffer<int32_t>* nonzero) {
  auto error = [l](const Status& status, const char* what) {
    return Status(status.code(), "grid level " + std::to_string(l) + what + status.message());
  };
  if (!reader->ReadFiniteF32(step)) return error(BitstreamError(""), ": bad or missing step");

  const int n = (r + kBrickSize - 1) / kBrickSize;
  const uint32_t num_bricks = static_cast<uint32_t>(n) * n * n;
  flags->resize(num_bricks);
  Status status = ReadSymbolBlock(reader, layout, num_bricks, 0, 1, flags->data());
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
  status = ReadSymbolBlock(reader, layout, count, -32768, 32767, coded->data());
  if (!status.ok()) return error(status, " values: ");

  const size_t rs = static_cast<size_t>(r);
  const size_t dense_size = rs * rs * rs * static_cast<size_t>(c);
  const bool incremental = values->size() == dense_size && nonzero->size() == num_bricks;
  if (!incremental) {
    values->resize(dense_size);
    std::memset(values->data(), 0, dense_size * sizeof(int16_t));  // assign() is no memset
  }
  const int32_t* src = coded->data();
  int b = 0;
  for (int bz = 0; bz < n; ++bz) {
    for (int by = 0; by < n; ++by) {
      for (int bx = 0; bx < n; ++bx, ++b) {
        const BrickBox box = BrickAt(bx, by, bz, r);
        if ((*flags)[b]) {
          src = FillBrick(box, r, c, src, values->data());
        } else if (incremental && (*nonzero)[b]) {
          FillBrick(box, r, c, nullptr, values->data());
        }
      }
    }
  }
  nonzero->swap(*flags);
  return Status::Ok();
}

// Zeroes values[l] where it was last read, or all of it when that is unknown or its size
// changes.
void ClearLevel(size_t dense_size, int c, MotionGrid* grid, int l) {
  Buffer<int16_t>& values = grid->values[l];
  if (values.size() != dense_size || !grid->active_valid[l]) {
    values.resize(dense_size);
    std::memset(values.data(), 0, dense_size * sizeof(int16_t));  // assign() is no memset
    return;
  }
  for (uint32_t v : grid->active_voxels[l]) {
    std::memset(&values[static_cast<size_t>(v) * c], 0, c * sizeof(int16_t));
  }
}

// Reads level(l) of the active-voxel syntax (spec 4.4, 0.10 on).
Status ReadActiveLevel(ByteReader* reader, RansLayout layout, int l, int r, int c,
                       const float* positions, size_t count, Buffer<int32_t>* coded,
                       MotionGrid* grid) {
  auto error = [l](const Status& status, const char* what) {
    return Status(status.code(), "grid level " + std::to_string(l) + what + status.message());
  };
  if (!reader->ReadFiniteF32(&grid->step[l])) {
    return error(BitstreamError(""), ": bad or missing step");
  }
  const size_t words = ActiveVoxelWords(r);
  grid->active_bitmap.assign(words, 0);
  MarkActiveVoxels(grid->box_min, grid->box_scale, r, positions, count, grid->active_bitmap.data());
  const size_t rs = static_cast<size_t>(r);
  ClearLevel(rs * rs * rs * static_cast<size_t>(c), c, grid, l);
  Buffer<uint32_t>& active = grid->active_voxels[l];
  active.clear();
  AppendActiveVoxels(grid->active_bitmap.data(), words, &active);
  grid->active_valid[l] = true;

  // At most R_l^3 * C_l values, which the sequence header limits.
  coded->resize(active.size() * static_cast<size_t>(c));
  const Status status = ReadSymbolBlock(reader, layout, static_cast<uint32_t>(coded->size()),
                                        -32768, 32767, coded->data());
  if (!status.ok()) return error(status, " values: ");
  const int32_t* src = coded->data();
  for (uint32_t v : active) {
    int16_t* dst = &grid->values[l][static_cast<size_t>(v) * c];
    for (int k = 0; k < c; ++k) dst[k] = static_cast<int16_t>(*src++);
  }
  return Status::Ok();
}

Status ReadGridBox(ByteReader* reader, MotionGrid* grid) {
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
  return Status::Ok();
}

// Levels the configuration no longer has give their memory back.
void ReleaseUnusedLevels(const GridConfig& config, MotionGrid* grid) {
  for (int l = config.num_levels; l < kMaxGridLevels; ++l) {
    grid->values[l] = Buffer<int16_t>(grid->values[l].get_allocator());
    grid->nonzero_bricks[l] = Buffer<int32_t>(grid->nonzero_bricks[l].get_allocator());
    grid->active_voxels[l] = Buffer<uint32_t>(grid->active_voxels[l].get_allocator());
    grid->active_valid[l] = false;
  }
}

}  // namespace

Status ReadMotionGrid(ByteReader* reader, RansLayout layout, const GridConfig& config,
                      MotionGrid* grid) {
  M4D_RETURN_IF_ERROR(ReadGridBox(reader, grid));
  const HookedAllocator<int32_t> alloc(grid->values[0].get_allocator());
  Buffer<int32_t> flags(alloc);
  Buffer<int32_t> coded(alloc);
  for (int l = 0; l < config.num_levels; ++l) {
    grid->active_valid[l] = false;
    M4D_RETURN_IF_ERROR(ReadLevel(reader, layout, l, config.resolution[l], config.channels[l],
                                  &flags, &coded, &grid->step[l], &grid->values[l],
                                  &grid->nonzero_bricks[l]));
  }
  ReleaseUnusedLevels(config, grid);
  return Status::Ok();
}

Status ReadActiveMotionGrid(ByteReader* reader, RansLayout layout, const GridConfig& config,
                            const float* positions, size_t count, MotionGrid* grid) {
  M4D_RETURN_IF_ERROR(ReadGridBox(reader, grid));
  Buffer<int32_t> coded(HookedAllocator<int32_t>(grid->values[0].get_allocator()));
  for (int l = 0; l < config.num_levels; ++l) {
    grid->nonzero_bricks[l].clear();  // the brick reader's state no longer describes values[l]
    M4D_RETURN_IF_ERROR(ReadActiveLevel(reader, layout, l, config.resolution[l], config.channels[l],
                                        positions, count, &coded, grid));
  }
  ReleaseUnusedLevels(config, grid);
  return Status::Ok();
}

}  // namespace m4d
