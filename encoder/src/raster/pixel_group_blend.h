// Front-to-back blending of a pixel group: eight horizontally adjacent pixels of one tile row,
// one per lane. This walk makes every decision of the rasterizer (which splat touches which
// pixel, which alpha is skipped, where a pixel stops), and both the forward pass and the
// backward pass's replay call it, so they agree bit for bit.
//
// A splat is evaluated at a pixel only if the pixel centre lies within its extent around the
// mean (splat_projection.h): the 3-sigma square of the reference rasterizer, applied per
// pixel rather than per tile so that the image does not depend on the tiling, narrowed to
// where alpha can reach 1/255.
#ifndef M4D_ENCODER_RASTER_PIXEL_GROUP_BLEND_H_
#define M4D_ENCODER_RASTER_PIXEL_GROUP_BLEND_H_

#include <cstddef>
#include <cstdint>

#include "encoder/src/raster/tile_splats.h"
#include "sdk/src/render/lanes.h"
#include "sdk/src/render/splat_alpha.h"

namespace m4d {

struct PixelGroup {
  int x0 = 0, y = 0;  // first pixel's column, row
  Lanes px;           // pixel centres, x0 + lane + 0.5
  float py = 0;       // row centre, y + 0.5
  Lanes transmittance;
  LaneMask done;  // lanes that stopped or lie outside the image
  LaneMask last;  // 1 + tile position of the last splat blended into the lane (0: none)
};

inline PixelGroup StartPixelGroup(int x0, int y, int width) {
  PixelGroup g;
  g.x0 = x0;
  g.y = y;
  g.py = static_cast<float>(y) + 0.5f;
  for (int l = 0; l < kLanes; ++l) {
    g.px[l] = static_cast<float>(x0 + l) + 0.5f;
    g.done[l] = x0 + l < width ? 0 : -1;
  }
  g.transmittance = Broadcast(1.0f);
  g.last = LaneMask{};
  return g;
}

// Walks the tile's splats front to back, blending into the group until every lane is done.
// For each candidate splat j (one whose extent reaches the group) it calls
//   on_blend(j, alpha, transmittance, blended)
// with alpha zero in the lanes it does not blend into, the transmittance in front of it,
// and blended false when that is every lane. The update itself has no data-dependent
// branches (they would mispredict), and doneness is checked once per eight splats.
template <typename OnBlend>
inline void BlendPixelGroup(const TileSplats& s, PixelGroup* g, OnBlend&& on_blend) {
  const float first_x = g->px[0], last_x = g->px[kLanes - 1];
  for (size_t base = 0; base < s.count; base += kLanes) {
    // Splats whose extent reaches this row and some lane of the group; conservative with
    // respect to the per-lane test below (same subtractions, monotone rounding).
    const Lanes ex = LoadLanes(s.extent_x + base), ey = LoadLanes(s.extent_y + base);
    const Lanes dy8 = LoadLanes(s.mean_y + base) - g->py;
    const Lanes mx = LoadLanes(s.mean_x + base);
    const Lanes dx_first = mx - first_x, dx_last = mx - last_x;
    unsigned hits = MaskBits((dy8 <= ey) & (dy8 >= -ey) & (dx_last <= ex) & (dx_first >= -ex));
    while (hits != 0) {
      const size_t j = base + static_cast<size_t>(__builtin_ctz(hits));
      hits &= hits - 1;
      const float dy = s.mean_y[j] - g->py;
      const Lanes dx = s.mean_x[j] - g->px;
      const float extent = s.extent_x[j];
      const Lanes power = SplatPower(dx, dy, s.conic_a[j], s.conic_b[j], s.conic_c[j]);
      const Lanes raw = s.opacity[j] * ExpNonPositive(power);
      const Lanes alpha = raw < kMaxAlpha ? raw : Broadcast(kMaxAlpha);
      LaneMask blend =
          (dx <= extent) & (dx >= -extent) & (power <= 0.0f) & (alpha >= kMinAlpha) & ~g->done;
      const Lanes next_t = g->transmittance * (1.0f - alpha);
      const LaneMask stop = blend & (next_t < kMinTransmittance);
      g->done |= stop;
      blend &= ~stop;
      on_blend(j, blend ? alpha : Lanes{}, g->transmittance, AnyLane(blend));
      g->transmittance = blend ? next_t : g->transmittance;
      g->last = blend ? static_cast<int32_t>(j + 1) : g->last;
    }
    if (AllLanes(g->done)) return;
  }
}

}  // namespace m4d

#endif  // M4D_ENCODER_RASTER_PIXEL_GROUP_BLEND_H_
