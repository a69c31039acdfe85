#include "encoder/src/raster/tile_rasterizer.h"

#include <algorithm>

#include "encoder/src/raster/pixel_group_blend.h"
#include "sdk/src/render/lanes.h"
#include "sdk/src/render/projection_constants.h"

namespace m4d {
namespace {

Lanes LoadRow(const float* row, int x0, int width) {
  Lanes v{};
  for (int l = 0; l < kLanes && x0 + l < width; ++l) v[l] = row[x0 + l];
  return v;
}

template <bool kWeights>
void RasterizeGroup(const TileSplats& s, int x0, int y, const TileTarget& target,
                    float* entry_weights) {
  PixelGroup group = StartPixelGroup(x0, y, target.width);
  const size_t row = static_cast<size_t>(y) * target.width;
  const Lanes error = kWeights && target.error_image
                          ? LoadRow(target.error_image + row, x0, target.width)
                          : Lanes{};
  Lanes color[3] = {};
  BlendPixelGroup(s, &group, [&](size_t j, const Lanes& alpha, const Lanes& t, bool) {
    // Lanes that do not blend have weight zero and add exact zeros.
    const Lanes w = alpha * t;
    for (int c = 0; c < 3; ++c) color[c] += s.color[c][j] * w;
    if (kWeights) {
      entry_weights[2 * j] += LaneSum(w);
      entry_weights[2 * j + 1] += LaneSum(w * error);
    }
  });
  for (int l = 0; l < kLanes && x0 + l < target.width; ++l) {
    const size_t p = row + x0 + l;
    const float t = group.transmittance[l];
    for (int c = 0; c < 3; ++c) target.color[3 * p + c] = color[c][l] + t * target.background[c];
    target.alpha[p] = 1.0f - t;
    target.final_transmittance[p] = t;
    target.last_contributor[p] = static_cast<uint32_t>(group.last[l]);
  }
}

}  // namespace

void RasterizeTile(const ProjectedSplats& splats, const TileBins& bins, size_t tile,
                   const TileTarget& target, TileSplatBuffer* buffer, float* accumulator) {
  const uint32_t begin = bins.tile_start[tile], end = bins.tile_start[tile + 1];
  const TileSplats& s = buffer->Gather(splats, bins.entries.data() + begin, end - begin);
  float* entry_weights = target.slot_weights ? accumulator : nullptr;
  if (entry_weights) std::fill(entry_weights, entry_weights + 2 * size_t{end - begin}, 0.0f);
  const int tx = static_cast<int>(tile % bins.tiles_x), ty = static_cast<int>(tile / bins.tiles_x);
  const int x_end = std::min(target.width, (tx + 1) * kTileSize);
  const int y_end = std::min(target.height, (ty + 1) * kTileSize);
  for (int y = ty * kTileSize; y < y_end; ++y) {
    for (int x0 = tx * kTileSize; x0 < x_end; x0 += kLanes) {
      if (entry_weights) {
        RasterizeGroup<true>(s, x0, y, target, entry_weights);
      } else {
        RasterizeGroup<false>(s, x0, y, target, nullptr);
      }
    }
  }
  if (!entry_weights) return;
  for (uint32_t j = 0; j < end - begin; ++j) {
    float* slot = target.slot_weights + 2 * size_t{bins.entry_slot[begin + j]};
    slot[0] = entry_weights[2 * j];
    slot[1] = entry_weights[2 * j + 1];
  }
}

void ClearTile(const TileBins& bins, size_t tile, const TileTarget& target) {
  const int tx = static_cast<int>(tile % bins.tiles_x), ty = static_cast<int>(tile / bins.tiles_x);
  const int x_end = std::min(target.width, (tx + 1) * kTileSize);
  const int y_end = std::min(target.height, (ty + 1) * kTileSize);
  for (int y = ty * kTileSize; y < y_end; ++y) {
    for (int x = tx * kTileSize; x < x_end; ++x) {
      const size_t p = static_cast<size_t>(y) * target.width + x;
      for (int c = 0; c < 3; ++c) target.color[3 * p + c] = target.background[c];
      target.alpha[p] = 0.0f;
      target.final_transmittance[p] = 1.0f;
      target.last_contributor[p] = 0;
    }
  }
  if (!target.slot_weights) return;
  for (uint32_t k = bins.tile_start[tile]; k < bins.tile_start[tile + 1]; ++k) {
    std::fill_n(target.slot_weights + 2 * size_t{bins.entry_slot[k]}, 2, 0.0f);
  }
}

}  // namespace m4d
