// RenderSettings: how RenderForward renders (see splat_renderer.h).
#ifndef M4D_ENCODER_RASTER_RENDER_SETTINGS_H_
#define M4D_ENCODER_RASTER_RENDER_SETTINGS_H_

#include <cstddef>

namespace m4d {

constexpr size_t kMaxRenderGaussians = size_t{1} << 24;  // summed over layers
constexpr int kMaxRenderThreads = 256;

struct RenderSettings {
  // Worker threads including the caller's; 0: the hardware's concurrency.
  int threads = 0;
  // Active SH degree (0..3): each layer is evaluated up to min(sh_degree, its own degree).
  int sh_degree = 3;
  // Composited behind the splats: colour = C + T_final * background.
  float background[3] = {0.0f, 0.0f, 0.0f};
  // Also accumulate, per Gaussian, its blend weight sum_p alpha_i(p) T_i(p) over all pixels.
  bool blend_weights = false;
  // With focus_layer >= 0, only the tiles that the splats of layers focus_layer.. can touch,
  // each grown by focus_margin tiles, are rendered (tile_focus.h); the others hold the
  // background with alpha 0 and give no blend weight. -1: every tile.
  int focus_layer = -1;
  int focus_margin = 1;
};

}  // namespace m4d

#endif  // M4D_ENCODER_RASTER_RENDER_SETTINGS_H_
