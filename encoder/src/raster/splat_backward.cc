#include "encoder/src/raster/splat_backward.h"

#include <algorithm>
#include <new>

#include "sdk/src/render/projection_constants.h"

namespace m4d {
namespace {

constexpr size_t kGaussianChunk = 256;

Status InvalidArg(const char* message) { return Status(M4D_ERR_INVALID_ARG, message); }

// A layer whose gradient arrays are all null gets none (its Gaussians are not trained).
bool Frozen(const LayerGradients& g) {
  return !g.positions && !g.log_scales && !g.rotations && !g.opacity_logits && !g.sh;
}

Status ValidateOutputs(const RenderContext& ctx, const SplatGradients& out) {
  if (out.layer_count != static_cast<int>(ctx.layers.size()) ||
      (out.layer_count > 0 && !out.layers)) {
    return InvalidArg("backward: gradient layers differ from the rendered layers");
  }
  for (int l = 0; l < out.layer_count; ++l) {
    const LayerGradients& g = out.layers[l];
    if (ctx.layers[l].count > 0 && !Frozen(g) &&
        (!g.positions || !g.log_scales || !g.rotations || !g.opacity_logits || !g.sh)) {
      return InvalidArg("backward: null gradient array");
    }
  }
  return Status::Ok();
}

// Blending backward over all tiles. False if a replay differed from the forward pass.
bool BackpropagateTiles(const float* dl_dcolor, const float* dl_dalpha, uint32_t first_trainable,
                        RenderContext* ctx, BackwardWorkspace* ws) {
  TileGradientTarget target;
  target.width = ctx->camera.width;
  target.height = ctx->camera.height;
  target.background = ctx->settings.background;
  target.dl_dcolor = dl_dcolor;
  target.dl_dalpha = dl_dalpha;
  target.final_transmittance = ctx->final_transmittance.data();
  target.last_contributor = ctx->last_contributor.data();
  target.slot_gradients = ws->slot_gradients.data();
  target.first_trainable = first_trainable;
  const size_t tiles = static_cast<size_t>(ctx->bins.tiles_x) * ctx->bins.tiles_y;
  ctx->pool->Run(tiles, [&](size_t tile, int worker) {
    if (!BackpropagateTile(ctx->splats, ctx->bins, tile, target, &ctx->tile_buffers[worker],
                           &ws->records[worker], ws->accumulators[worker].data())) {
      ws->replay_mismatch[worker] = 1;
    }
  });
  return std::find(ws->replay_mismatch.begin(), ws->replay_mismatch.end(), 1) ==
         ws->replay_mismatch.end();
}

// The Gaussians of the leading frozen layers, which need no gradient unless every splat's 2D
// gradients were asked for. A focused pass rendered only the tiles the focus layers reach, so
// the layers before them get no gradients at all.
uint32_t FirstTrainable(const RenderContext& ctx, const SplatGradients& out) {
  const int focus = std::max(0, ctx.settings.focus_layer);
  size_t first = 0;
  for (int l = 0; l < out.layer_count; ++l) {
    if (l >= focus && (out.mean2d || out.color || !Frozen(out.layers[l]))) break;
    first += ctx.layers[l].count;
  }
  return static_cast<uint32_t>(first);
}

// Sums the gradients of Gaussian g over its tiles, in a fixed order.
SplatGradient GatherSplatGradient(const RenderContext& ctx, const BackwardWorkspace& ws, size_t g) {
  float sum[kEntryGradients] = {};
  for (size_t k = ctx.bins.gaussian_start[g]; k < ctx.bins.gaussian_start[g + 1]; ++k) {
    const float* e = &ws.slot_gradients[kEntryGradients * k];
    for (int f = 0; f < kEntryGradients; ++f) sum[f] += e[f];
  }
  SplatGradient grad;
  grad.mean[0] = sum[kGradMeanX];
  grad.mean[1] = sum[kGradMeanY];
  grad.conic[0] = sum[kGradConicA];
  grad.conic[1] = sum[kGradConicB];
  grad.conic[2] = sum[kGradConicC];
  grad.opacity = sum[kGradOpacity];
  for (int c = 0; c < 3; ++c) grad.color[c] = sum[kGradColorR + c];
  return grad;
}

// Gaussians before first_trainable get zero 2D gradients: their tiles may not be replayed.
void BackpropagateGaussians(const SplatGradients& out, uint32_t first_trainable, RenderContext* ctx,
                            const BackwardWorkspace& ws) {
  const ProjectionConstants pc = MakeProjectionConstants(ctx->camera);
  ParallelForChunks(ctx->pool.get(), ctx->gaussian_count, kGaussianChunk,
                    [&](size_t begin, size_t end, int) {
                      size_t offset = 0;
                      for (int l = 0; l < out.layer_count; ++l) {
                        const M4dGaussians& layer = ctx->layers[l];
                        const size_t lo = std::max(begin, offset);
                        const size_t hi = std::min(end, offset + layer.count);
                        const bool frozen = Frozen(out.layers[l]);
                        for (size_t g = lo; g < hi; ++g) {
                          const size_t i = g - offset;
                          SplatGradient grad = {};
                          if (ctx->splats.radius[g] == 0.0f) {
                            if (!frozen) ZeroGradients(layer, i, out.layers[l]);
                          } else if (frozen) {
                            if ((out.mean2d || out.color) && g >= first_trainable) {
                              grad = GatherSplatGradient(*ctx, ws, g);
                            }
                          } else {
                            grad = GatherSplatGradient(*ctx, ws, g);
                            BackpropagateProjection(pc, layer, ctx->settings.sh_degree, i, grad,
                                                    ctx->splats.color_clamped[g], out.layers[l]);
                          }
                          if (out.mean2d) {
                            out.mean2d[2 * g] = grad.mean[0];
                            out.mean2d[2 * g + 1] = grad.mean[1];
                          }
                          if (out.color) std::copy_n(grad.color, 3, out.color + 3 * g);
                        }
                        offset += layer.count;
                      }
                    });
}

}  // namespace

Status RenderBackward(const float* dl_dcolor, const float* dl_dalpha, RenderContext* context,
                      const SplatGradients& out, BackwardWorkspace* workspace) {
  if (!dl_dcolor || !context || !workspace) return InvalidArg("backward: null argument");
  if (!context->valid) return InvalidArg("backward: no successful forward pass");
  M4D_RETURN_IF_ERROR(ValidateOutputs(*context, out));
  try {
    const size_t workers = static_cast<size_t>(context->pool->size());
    const size_t max_entries = context->bins.max_tile_entries;
    workspace->slot_gradients.resize(kEntryGradients * context->bins.entries.size());
    workspace->records.resize(workers);
    workspace->accumulators.resize(workers);
    for (size_t w = 0; w < workers; ++w) {
      workspace->records[w].Reserve(max_entries);
      if (workspace->accumulators[w].size() < kEntryGradients * max_entries) {
        workspace->accumulators[w].resize(kEntryGradients * max_entries);
      }
    }
    workspace->replay_mismatch.assign(workers, 0);
  } catch (const std::bad_alloc&) {
    return Status(M4D_ERR_NOMEM, "backward: out of memory");
  }
  const uint32_t first_trainable = FirstTrainable(*context, out);
  if (!BackpropagateTiles(dl_dcolor, dl_dalpha, first_trainable, context, workspace)) {
    return InvalidArg("backward: the forward pass's state was modified");
  }
  BackpropagateGaussians(out, first_trainable, context, *workspace);
  return Status::Ok();
}

}  // namespace m4d
