// Tile binning: every visible splat is listed in each 16x16 tile its rectangle covers,
// front to back. One global sort of the visible splats by depth (radix, stable, ties in index
// order), then a stable fill of the per-tile lists, in parallel over chunks of the sorted
// order; the result does not depend on the thread count.
#ifndef M4D_ENCODER_RASTER_TILE_BINNING_H_
#define M4D_ENCODER_RASTER_TILE_BINNING_H_

#include <cstddef>
#include <cstdint>
#include <vector>

#include "sdk/src/common/status.h"
#include "sdk/src/common/thread_pool.h"
#include "sdk/src/render/projected_splats.h"

namespace m4d {

// Largest number of (splat, tile) pairs a render may produce; more fails with M4D_ERR_LIMIT.
constexpr size_t kMaxTileEntries = size_t{1} << 26;

struct TileBins {
  int tiles_x = 0, tiles_y = 0;
  // Entries of tile t (row-major) are entries[tile_start[t] .. tile_start[t + 1]): Gaussian
  // indices, front to back.
  std::vector<uint32_t> tile_start;
  std::vector<uint32_t> entries;
  // Gaussian g's entries, one per tile of its rectangle in row-major order, have the slots
  // gaussian_start[g] .. gaussian_start[g + 1]; entry_slot maps an entry to its slot.
  // Per-entry results are stored by slot, so that summing them per Gaussian reads memory
  // in order.
  std::vector<uint32_t> gaussian_start;
  std::vector<uint32_t> entry_slot;
  size_t max_tile_entries = 0;

  // Scratch reused between renders.
  std::vector<uint32_t> keys, order, key_scratch, order_scratch;
  std::vector<uint16_t> sorted_rect;   // tile rectangles in depth order
  std::vector<uint32_t> chunk_cursor;  // per chunk and tile
};

// Bins the splats of `splats` (radius 0: culled) into tiles_x x tiles_y tiles.
Status BinSplats(const ProjectedSplats& splats, int tiles_x, int tiles_y, ThreadPool* pool,
                 TileBins* bins);

}  // namespace m4d

#endif  // M4D_ENCODER_RASTER_TILE_BINNING_H_
