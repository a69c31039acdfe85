#include "encoder/src/raster/tile_binning.h"

#include <algorithm>
#include <cstring>

#include "sdk/src/render/radix_sort.h"

namespace m4d {
namespace {

// Calls visit(tile) for each tile of a rectangle (first column, row, last column, row),
// row-major.
template <typename Visit>
void ForEachTile(const uint16_t* rect, int tiles_x, Visit&& visit) {
  for (int ty = rect[1]; ty <= rect[3]; ++ty) {
    for (int tx = rect[0]; tx <= rect[2]; ++tx) visit(static_cast<size_t>(ty) * tiles_x + tx);
  }
}

// Lists the visible Gaussians with their depth keys and numbers their entries. False when
// there are more than kMaxTileEntries.
bool CountEntries(const ProjectedSplats& splats, TileBins* bins) {
  const size_t n = splats.size();
  bins->gaussian_start.resize(n + 1);
  bins->keys.clear();
  bins->order.clear();
  size_t total = 0;
  for (size_t g = 0; g < n; ++g) {
    bins->gaussian_start[g] = static_cast<uint32_t>(total);
    if (splats.radius[g] == 0.0f) continue;
    const uint16_t* rect = &splats.tile_rect[4 * g];
    total += static_cast<size_t>(rect[2] - rect[0] + 1) * (rect[3] - rect[1] + 1);
    if (total > kMaxTileEntries) return false;
    uint32_t key;
    std::memcpy(&key, &splats.depth[g], sizeof(key));  // depth > 0: bits sort like the float
    bins->keys.push_back(key);
    bins->order.push_back(static_cast<uint32_t>(g));
  }
  bins->gaussian_start[n] = static_cast<uint32_t>(total);
  return true;
}

}  // namespace

Status BinSplats(const ProjectedSplats& splats, int tiles_x, int tiles_y, ThreadPool* pool,
                 TileBins* bins) {
  bins->tiles_x = tiles_x;
  bins->tiles_y = tiles_y;
  if (!CountEntries(splats, bins)) return LimitError("render: too many (splat, tile) pairs");
  RadixSortPairs(&bins->keys, &bins->order, &bins->key_scratch, &bins->order_scratch);

  // Chunks of the sorted order count, then fill, their entries per tile; a chunk's entries
  // of a tile follow those of the chunks before it, which keeps every tile front to back.
  const size_t tiles = static_cast<size_t>(tiles_x) * tiles_y;
  const size_t visible = bins->order.size();
  const size_t chunks = std::max<size_t>(
      1, std::min({static_cast<size_t>(pool->size()), (size_t{1} << 22) / tiles, visible / 256}));
  const size_t per_chunk = (visible + chunks - 1) / chunks;
  bins->chunk_cursor.assign(chunks * tiles, 0);
  bins->sorted_rect.resize(4 * visible);
  auto chunk_range = [&](size_t c, size_t* begin, size_t* end) {
    *begin = std::min(visible, c * per_chunk);
    *end = std::min(visible, *begin + per_chunk);
  };
  pool->Run(chunks, [&](size_t c, int) {
    uint32_t* cursor = &bins->chunk_cursor[c * tiles];
    size_t begin, end;
    chunk_range(c, &begin, &end);
    // Gather the rectangles in depth order once: the counting and filling then read them
    // sequentially rather than at random.
    uint16_t* rects = bins->sorted_rect.data();
    for (size_t k = begin; k < end; ++k) {
      std::memcpy(rects + 4 * k, &splats.tile_rect[4 * size_t{bins->order[k]}],
                  4 * sizeof(uint16_t));
    }
    for (size_t k = begin; k < end; ++k) {
      ForEachTile(rects + 4 * k, tiles_x, [&](size_t t) { ++cursor[t]; });
    }
  });
  bins->tile_start.resize(tiles + 1);
  bins->max_tile_entries = 0;
  uint32_t sum = 0;
  for (size_t t = 0; t < tiles; ++t) {
    bins->tile_start[t] = sum;
    for (size_t c = 0; c < chunks; ++c) {
      const uint32_t here = bins->chunk_cursor[c * tiles + t];
      bins->chunk_cursor[c * tiles + t] = sum;
      sum += here;
    }
    bins->max_tile_entries = std::max<size_t>(bins->max_tile_entries, sum - bins->tile_start[t]);
  }
  bins->tile_start[tiles] = sum;
  bins->entries.resize(sum);
  bins->entry_slot.resize(sum);
  pool->Run(chunks, [&](size_t c, int) {
    uint32_t* cursor = &bins->chunk_cursor[c * tiles];
    size_t begin, end;
    chunk_range(c, &begin, &end);
    for (size_t k = begin; k < end; ++k) {
      const uint32_t g = bins->order[k];
      uint32_t slot = bins->gaussian_start[g];
      ForEachTile(&bins->sorted_rect[4 * k], tiles_x, [&](size_t t) {
        const uint32_t pos = cursor[t]++;
        bins->entries[pos] = g;
        bins->entry_slot[pos] = slot++;
      });
    }
  });
  return Status::Ok();
}

}  // namespace m4d
