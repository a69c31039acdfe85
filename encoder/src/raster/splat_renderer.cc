#include "encoder/src/raster/splat_renderer.h"

#include <algorithm>
#include <cmath>
#include <new>

#include "encoder/src/raster/tile_rasterizer.h"
#include "sdk/src/render/projection_constants.h"
#include "sdk/src/render/splat_projection.h"

namespace m4d {
namespace {

constexpr size_t kGaussianChunk = 512;

Status InvalidArg(const char* message) { return Status(M4D_ERR_INVALID_ARG, message); }

Status ValidateSettings(const RenderSettings& s) {
  if (s.threads < 0 || s.threads > kMaxRenderThreads) {
    return InvalidArg("render: thread count out of range");
  }
  if (s.sh_degree < 0 || s.sh_degree > 3) return InvalidArg("render: SH degree out of range");
  if (s.focus_layer < -1 || s.focus_margin < 0 || s.focus_margin > 1024) {
    return InvalidArg("render: focus out of range");
  }
  for (float b : s.background) {
    if (!std::isfinite(b)) return InvalidArg("render: background must be finite");
  }
  return Status::Ok();
}

Status ValidateLayers(const M4dGaussians* layers, int layer_count) {
  if (layer_count < 0 || (layer_count > 0 && !layers)) {
    return InvalidArg("render: bad layer list");
  }
  size_t total = 0;
  for (int l = 0; l < layer_count; ++l) {
    const M4dGaussians& v = layers[l];
    if (v.sh_degree > 3) return InvalidArg("render: layer SH degree above 3");
    if (v.count > kMaxRenderGaussians - total) return LimitError("render: too many Gaussians");
    total += v.count;
    if (v.count > 0 &&
        (!v.positions || !v.log_scales || !v.rotations || !v.opacity_logits || !v.sh)) {
      return InvalidArg("render: layer with null arrays");
    }
  }
  return Status::Ok();
}

void PrepareState(const Camera& camera, const M4dGaussians* layers, int layer_count,
                  const RenderSettings& settings, RenderContext* ctx) {
  if (!ctx->pool || ctx->pool_threads != settings.threads) {
    ctx->pool.reset();
    ctx->pool = std::make_unique<ThreadPool>(settings.threads);
    ctx->pool_threads = settings.threads;
  }
  ctx->camera = camera;
  ctx->settings = settings;
  ctx->layers.assign(layers, layers + layer_count);
  ctx->gaussian_count = 0;
  for (const M4dGaussians& v : ctx->layers) ctx->gaussian_count += v.count;
}

// Projects every layer, or copies the first one's given projection.
void Project(const ProjectionConstants& pc, const ProjectedSplats* first_layer,
             RenderContext* ctx) {
  ctx->splats.Resize(ctx->gaussian_count);
  ParallelForChunks(ctx->pool.get(), ctx->gaussian_count, kGaussianChunk,
                    [&](size_t begin, size_t end, int) {
                      size_t offset = 0;
                      for (size_t l = 0; l < ctx->layers.size(); ++l) {
                        const M4dGaussians& layer = ctx->layers[l];
                        const size_t lo = std::max(begin, offset);
                        const size_t hi = std::min(end, offset + layer.count);
                        if (lo < hi && l == 0 && first_layer) {
                          ctx->splats.CopyRange(*first_layer, lo, hi);
                        } else if (lo < hi) {
                          ProjectSplats(pc, layer, ctx->settings.sh_degree, lo - offset,
                                        hi - offset, offset, &ctx->splats);
                        }
                        offset += layer.count;
                      }
                    });
}

// All tiles, or those of settings.focus_layer's focus (the other splats clipped to its
// bounding rectangle).
void Focus(const ProjectionConstants& pc, RenderContext* ctx) {
  const int layer = ctx->settings.focus_layer;
  if (layer < 0) {
    FocusAll(pc.tiles_x, pc.tiles_y, &ctx->focus);
    return;
  }
  size_t first = 0;
  for (int l = 0; l < layer && l < static_cast<int>(ctx->layers.size()); ++l) {
    first += ctx->layers[l].count;
  }
  FocusOn(ctx->splats, first, ctx->settings.focus_margin, pc.tiles_x, pc.tiles_y, &ctx->focus);
  ClipToFocus(ctx->focus.rect, &ctx->splats);
}

void Rasterize(const float* error_image, RenderContext* ctx) {
  const size_t pixels = static_cast<size_t>(ctx->camera.width) * ctx->camera.height;
  ctx->color.resize(3 * pixels);
  ctx->alpha.resize(pixels);
  ctx->final_transmittance.resize(pixels);
  ctx->last_contributor.resize(pixels);
  const bool weights = ctx->settings.blend_weights || error_image;
  ctx->slot_weights.resize(weights ? 2 * ctx->bins.entries.size() : 0);
  const size_t workers = static_cast<size_t>(ctx->pool->size());
  ctx->tile_buffers.resize(workers);
  ctx->tile_accumulators.resize(workers);
  for (size_t w = 0; w < workers; ++w) {
    ctx->tile_buffers[w].Reserve(ctx->bins.max_tile_entries);
    if (weights && ctx->tile_accumulators[w].size() < 2 * ctx->bins.max_tile_entries) {
      ctx->tile_accumulators[w].resize(2 * ctx->bins.max_tile_entries);
    }
  }

  TileTarget target;
  target.width = ctx->camera.width;
  target.height = ctx->camera.height;
  target.background = ctx->settings.background;
  target.color = ctx->color.data();
  target.alpha = ctx->alpha.data();
  target.final_transmittance = ctx->final_transmittance.data();
  target.last_contributor = ctx->last_contributor.data();
  target.slot_weights = weights ? ctx->slot_weights.data() : nullptr;
  target.error_image = error_image;
  const size_t tiles = static_cast<size_t>(ctx->bins.tiles_x) * ctx->bins.tiles_y;
  ctx->pool->Run(tiles, [&](size_t tile, int worker) {
    if (!ctx->focus.rendered(tile)) {
      ClearTile(ctx->bins, tile, target);
      return;
    }
    RasterizeTile(ctx->splats, ctx->bins, tile, target, &ctx->tile_buffers[worker],
                  ctx->tile_accumulators[worker].data());
  });
}

// Sums each Gaussian's weights over its tiles, in a fixed order.
void ReduceBlendWeights(bool blend_weights, bool error_weights, RenderContext* ctx) {
  const size_t n = ctx->gaussian_count;
  ctx->blend_weight.assign(blend_weights ? n : 0, 0.0f);
  ctx->error_weight.assign(error_weights ? n : 0, 0.0f);
  if (!blend_weights && !error_weights) return;
  ParallelForChunks(ctx->pool.get(), n, kGaussianChunk, [&](size_t begin, size_t end, int) {
    const TileBins& bins = ctx->bins;
    for (size_t g = begin; g < end; ++g) {
      float w = 0.0f, e = 0.0f;
      for (size_t k = bins.gaussian_start[g]; k < bins.gaussian_start[g + 1]; ++k) {
        w += ctx->slot_weights[2 * k];
        e += ctx->slot_weights[2 * k + 1];
      }
      if (blend_weights) ctx->blend_weight[g] = w;
      if (error_weights) ctx->error_weight[g] = e;
    }
  });
}

}  // namespace

Status RenderForward(const Camera& camera, const M4dGaussians* layers, int layer_count,
                     const RenderSettings& settings, const float* error_image,
                     RenderContext* context) {
  return RenderForward(camera, layers, layer_count, settings, error_image, nullptr, context);
}

Status RenderForward(const Camera& camera, const M4dGaussians* layers, int layer_count,
                     const RenderSettings& settings, const float* error_image,
                     const ProjectedSplats* first_layer, RenderContext* context) {
  if (!context) return InvalidArg("render: null context");
  context->valid = false;
  M4D_RETURN_IF_ERROR(ValidateCamera(camera));
  M4D_RETURN_IF_ERROR(ValidateSettings(settings));
  M4D_RETURN_IF_ERROR(ValidateLayers(layers, layer_count));
  if (first_layer && (layer_count == 0 || first_layer->size() != layers[0].count)) {
    return InvalidArg("render: the first layer's projection has another size");
  }
  try {
    PrepareState(camera, layers, layer_count, settings, context);
    const ProjectionConstants pc = MakeProjectionConstants(camera);
    Project(pc, first_layer, context);
    Focus(pc, context);
    M4D_RETURN_IF_ERROR(
        BinSplats(context->splats, pc.tiles_x, pc.tiles_y, context->pool.get(), &context->bins));
    Rasterize(error_image, context);
    ReduceBlendWeights(settings.blend_weights, error_image != nullptr, context);
  } catch (const std::bad_alloc&) {
    return Status(M4D_ERR_NOMEM, "render: out of memory");
  }
  context->valid = true;
  return Status::Ok();
}

Status ProjectLayer(const Camera& camera, const M4dGaussians& layer, int sh_degree,
                    ProjectedSplats* out) {
  M4D_RETURN_IF_ERROR(ValidateCamera(camera));
  if (sh_degree < 0 || sh_degree > 3) return InvalidArg("render: SH degree out of range");
  M4D_RETURN_IF_ERROR(ValidateLayers(&layer, 1));
  try {
    out->Resize(layer.count);
    ProjectSplats(MakeProjectionConstants(camera), layer, sh_degree, 0, layer.count, 0, out);
  } catch (const std::bad_alloc&) {
    return Status(M4D_ERR_NOMEM, "render: out of memory");
  }
  return Status::Ok();
}

}  // namespace m4d
