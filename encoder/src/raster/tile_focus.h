// Tile focus: a render restricted to the tiles that some layers' splats can touch, grown by a
// margin. The encoder's inter-frame training moves only the dynamic layer over a fixed static
// layer: every other tile is the same in every step and passes no gradient to what is trained,
// so rendering only the focus tiles gives the same trained gradients for a fraction of the work.
#ifndef M4D_ENCODER_RASTER_TILE_FOCUS_H_
#define M4D_ENCODER_RASTER_TILE_FOCUS_H_

#include <cstddef>
#include <cstdint>
#include <vector>

#include "sdk/src/render/projected_splats.h"

namespace m4d {

// Tiles: first column, first row, last column, last row (inclusive); empty when first > last.
struct TileRect {
  int x0 = 0, y0 = 0, x1 = -1, y1 = -1;
  bool empty() const { return x0 > x1 || y0 > y1; }
};

struct TileFocus {
  bool all = true;  // every tile is rendered (no focus)
  int tiles_x = 0, tiles_y = 0;
  std::vector<uint8_t> mask;  // per tile, row-major, without `all`: 1 rendered
  TileRect rect;              // the rendered tiles' bounding rectangle
  bool rendered(size_t tile) const { return all || mask[tile] != 0; }
};

// Every tile of a tiles_x x tiles_y grid.
void FocusAll(int tiles_x, int tiles_y, TileFocus* focus);

// The tiles that splats [first, splats.size()) can touch, each grown by `margin` tiles.
void FocusOn(const ProjectedSplats& splats, size_t first, int margin, int tiles_x, int tiles_y,
             TileFocus* focus);

// Clips every splat's tile rectangle to `rect`; splats outside it are culled (radius 0).
void ClipToFocus(const TileRect& rect, ProjectedSplats* splats);

}  // namespace m4d

#endif  // M4D_ENCODER_RASTER_TILE_FOCUS_H_
