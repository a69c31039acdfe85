#include "encoder/src/raster/tile_focus.h"

#include <algorithm>

namespace m4d {

void FocusAll(int tiles_x, int tiles_y, TileFocus* focus) {
  focus->all = true;
  focus->tiles_x = tiles_x;
  focus->tiles_y = tiles_y;
  focus->mask.clear();
  focus->rect = TileRect{0, 0, tiles_x - 1, tiles_y - 1};
}

void FocusOn(const ProjectedSplats& splats, size_t first, int margin, int tiles_x, int tiles_y,
             TileFocus* focus) {
  focus->all = false;
  focus->tiles_x = tiles_x;
  focus->tiles_y = tiles_y;
  focus->mask.assign(static_cast<size_t>(tiles_x) * tiles_y, 0);
  TileRect& box = focus->rect;
  box = TileRect{tiles_x, tiles_y, -1, -1};
  for (size_t g = first; g < splats.size(); ++g) {
    if (splats.radius[g] == 0.0f) continue;
    const uint16_t* r = &splats.tile_rect[4 * g];
    const int x0 = std::max(0, r[0] - margin), y0 = std::max(0, r[1] - margin);
    const int x1 = std::min(tiles_x - 1, r[2] + margin), y1 = std::min(tiles_y - 1, r[3] + margin);
    for (int ty = y0; ty <= y1; ++ty) {
      std::fill_n(&focus->mask[static_cast<size_t>(ty) * tiles_x + x0], x1 - x0 + 1, 1);
    }
    box = TileRect{std::min(box.x0, x0), std::min(box.y0, y0), std::max(box.x1, x1),
                   std::max(box.y1, y1)};
  }
}

void ClipToFocus(const TileRect& rect, ProjectedSplats* splats) {
  for (size_t g = 0; g < splats->size(); ++g) {
    if (splats->radius[g] == 0.0f) continue;
    uint16_t* r = &splats->tile_rect[4 * g];
    const int x0 = std::max<int>(r[0], rect.x0), y0 = std::max<int>(r[1], rect.y0);
    const int x1 = std::min<int>(r[2], rect.x1), y1 = std::min<int>(r[3], rect.y1);
    if (x0 > x1 || y0 > y1) {
      splats->radius[g] = 0.0f;
      continue;
    }
    r[0] = static_cast<uint16_t>(x0);
    r[1] = static_cast<uint16_t>(y0);
    r[2] = static_cast<uint16_t>(x1);
    r[3] = static_cast<uint16_t>(y1);
  }
}

}  // namespace m4d
