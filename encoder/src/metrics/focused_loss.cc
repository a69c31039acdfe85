#include "encoder/src/metrics/focused_loss.h"

#include <algorithm>
#include <cstring>

#include "sdk/src/render/projection_constants.h"

namespace m4d {
namespace {

struct PixelRect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // [x0, x1) x [y0, y1)
  int width() const { return x1 - x0; }
  int height() const { return y1 - y0; }
};

PixelRect TilePixels(const TileRect& focus, int width, int height) {
  PixelRect r;
  r.x0 = std::min(width, focus.x0 * kTileSize);
  r.y0 = std::min(height, focus.y0 * kTileSize);
  r.x1 = std::min(width, (focus.x1 + 1) * kTileSize);
  r.y1 = std::min(height, (focus.y1 + 1) * kTileSize);
  return r;
}

void Crop(const Image& from, const PixelRect& r, Image* to) {
  to->width = r.width();
  to->height = r.height();
  to->channels = from.channels;
  to->pixels.resize(static_cast<size_t>(r.width()) * r.height() * from.channels);
  const size_t row = static_cast<size_t>(r.width()) * from.channels;
  for (int y = 0; y < r.height(); ++y) {
    std::memcpy(to->row(y), from.row(r.y0 + y) + static_cast<size_t>(r.x0) * from.channels,
                row * sizeof(float));
  }
}

// The crop's pixels (tiles `tiles`) of tiles the render skipped: fill's.
void FillSkippedTiles(const TileFocus& focus, const TileRect& tiles, const PixelRect& r,
                      const Image& fill, Image* crop) {
  if (focus.all) return;
  for (int ty = tiles.y0; ty <= tiles.y1; ++ty) {
    for (int tx = tiles.x0; tx <= tiles.x1; ++tx) {
      if (focus.rendered(static_cast<size_t>(ty) * focus.tiles_x + tx)) continue;
      const PixelRect tile = TilePixels(TileRect{tx, ty, tx, ty}, fill.width, fill.height);
      for (int y = tile.y0; y < tile.y1; ++y) {
        std::memcpy(crop->row(y - r.y0) + static_cast<size_t>(tile.x0 - r.x0) * 3,
                    fill.row(y) + static_cast<size_t>(tile.x0) * 3,
                    static_cast<size_t>(tile.width()) * 3 * sizeof(float));
      }
    }
  }
}

}  // namespace

Status FocusedLoss::Evaluate(const Image& rendered, const Image& target, const TileFocus& focus,
                             const Image* unfocused, PhotometricLossValue* value, Image* grad) {
  if (rendered.width != target.width || rendered.height != target.height ||
      rendered.channels != 3 || target.channels != 3 ||
      (unfocused && (unfocused->width != target.width || unfocused->height != target.height ||
                     unfocused->channels != 3))) {
    return Status(M4D_ERR_INVALID_ARG, "focused loss: images differ in shape");
  }
  grad->width = rendered.width;
  grad->height = rendered.height;
  grad->channels = 3;
  grad->pixels.assign(rendered.pixels.size(), 0.0f);
  *value = PhotometricLossValue();
  if (focus.rect.empty()) return Status::Ok();
  TileRect tiles = focus.rect;
  if (unfocused && !focus.all) {
    tiles.x0 = std::max(0, tiles.x0 - 1);
    tiles.y0 = std::max(0, tiles.y0 - 1);
    tiles.x1 = std::min(focus.tiles_x - 1, tiles.x1 + 1);
    tiles.y1 = std::min(focus.tiles_y - 1, tiles.y1 + 1);
  }
  const PixelRect r = TilePixels(tiles, rendered.width, rendered.height);
  if (r.width() <= 0 || r.height() <= 0) return Status::Ok();
  Crop(rendered, r, &rendered_crop_);
  Crop(target, r, &target_crop_);
  FillSkippedTiles(focus, tiles, r, unfocused ? *unfocused : target, &rendered_crop_);
  M4D_RETURN_IF_ERROR(loss_.Evaluate(rendered_crop_, target_crop_, value, &grad_crop_));
  // The crop's loss is a mean over its pixels; the whole image's weighs each pixel less.
  const float share = static_cast<float>(static_cast<double>(rendered_crop_.pixels.size()) /
                                         static_cast<double>(rendered.pixels.size()));
  for (int y = 0; y < r.height(); ++y) {
    const float* from = grad_crop_.row(y);
    float* to = grad->row(r.y0 + y) + static_cast<size_t>(r.x0) * 3;
    for (int k = 0; k < 3 * r.width(); ++k) to[k] = share * from[k];
  }
  return Status::Ok();
}

}  // namespace m4d
