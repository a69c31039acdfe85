// RenderContext: the outputs of RenderForward and everything the backward pass needs from
// it, kept between renders so that repeated renders reuse their buffers.
#ifndef M4D_ENCODER_RASTER_RENDER_CONTEXT_H_
#define M4D_ENCODER_RASTER_RENDER_CONTEXT_H_

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "encoder/src/raster/render_settings.h"
#include "encoder/src/raster/tile_binning.h"
#include "encoder/src/raster/tile_focus.h"
#include "encoder/src/raster/tile_splats.h"
#include "sdk/src/common/thread_pool.h"
#include "sdk/src/layers/gaussian_views.h"
#include "sdk/src/render/camera.h"
#include "sdk/src/render/projected_splats.h"

namespace m4d {

struct RenderContext {
  // --- Outputs of the last render.
  std::vector<float> color;  // width * height * 3, RGB interleaved, row 0 at the top; not clamped
  std::vector<float> alpha;  // width * height: 1 - final transmittance
  // Per Gaussian (global index), when settings.blend_weights: sum over pixels of alpha * T.
  std::vector<float> blend_weight;
  // Per Gaussian, when an error image e was given: sum over pixels of alpha * T * e.
  std::vector<float> error_weight;
  // Per Gaussian: projected mean (pixels), depth, radius (0: culled), conic, opacity, colour.
  ProjectedSplats splats;
  // The tiles rendered: all of them, or with settings.focus_layer the focus (may be none).
  TileFocus focus;

  // --- State of the last render, for the backward pass. The layer views point at the
  // caller's arrays, which must stay unchanged until the backward pass has run.
  bool valid = false;  // the last RenderForward succeeded
  Camera camera;
  RenderSettings settings;
  std::vector<M4dGaussians> layers;
  size_t gaussian_count = 0;
  TileBins bins;
  std::vector<float> final_transmittance;  // per pixel
  std::vector<uint32_t> last_contributor;  // per pixel: 1 + tile position of the last splat

  // --- Workers and their scratch.
  std::unique_ptr<ThreadPool> pool;
  int pool_threads = -1;                              // the setting the pool was made for
  std::vector<TileSplatBuffer> tile_buffers;          // per worker
  std::vector<std::vector<float>> tile_accumulators;  // per worker, per tile entry
  std::vector<float> slot_weights;  // 2 per tile entry, by slot: weight, weighted error
};

}  // namespace m4d

#endif  // M4D_ENCODER_RASTER_RENDER_CONTEXT_H_
