// Forward blending of one tile: every pixel group of the tile walks the tile's splats front
// to back (pixel_group_blend.h) and writes its colour, alpha, final transmittance and last
// contributor; optionally each entry's blend weight and error-weighted blend weight, by slot
// (tile_binning.h).
#ifndef M4D_ENCODER_RASTER_TILE_RASTERIZER_H_
#define M4D_ENCODER_RASTER_TILE_RASTERIZER_H_

#include <cstddef>
#include <cstdint>

#include "encoder/src/raster/tile_binning.h"
#include "encoder/src/raster/tile_splats.h"
#include "sdk/src/render/projected_splats.h"

namespace m4d {

struct TileTarget {
  int width = 0, height = 0;
  const float* background = nullptr;  // 3 floats
  float* color = nullptr;
  float* alpha = nullptr;
  float* final_transmittance = nullptr;
  uint32_t* last_contributor = nullptr;
  // Optional: 2 floats per slot (sum of alpha T, sum of alpha T e), and the error image e
  // (width * height, or null for zero).
  float* slot_weights = nullptr;
  const float* error_image = nullptr;
};

// accumulator: per-worker scratch of at least 2 * bins.max_tile_entries floats, used when
// target.slot_weights is set.
void RasterizeTile(const ProjectedSplats& splats, const TileBins& bins, size_t tile,
                   const TileTarget& target, TileSplatBuffer* buffer, float* accumulator);

// A tile outside a render's focus (tile_focus.h): the background with alpha 0, and zero
// weights for its entries.
void ClearTile(const TileBins& bins, size_t tile, const TileTarget& target);

}  // namespace m4d

#endif  // M4D_ENCODER_RASTER_TILE_RASTERIZER_H_
