// The CPU splat rasterizer: forward (SDK) and forward + backward (encoder training step).
//
// Scene: Gaussians uniformly in the box [-2.5, 2.5] x [-1.9, 1.9] x [3, 8] in front of a
// camera at the origin (identity pose, fx = fy = image width, principal point at the
// centre, so the box fills the view); log-uniform scales in [0.015, 0.08] per axis (at
// 200x150 a projected sigma of about 0.6 to 4 pixels, radii of 3 to 12 pixels; 3.2 times
// that at 640x480), random rotations, opacity logits uniform in [-1.5, 1.5] (opacity 0.18 to
// 0.82), SH degree 3 with DC ~ N(0, 0.6) and higher coefficients ~ N(0, 0.1). The backward
// pass gets a fixed random dL/dcolour.
// Arguments: width, height, Gaussian count, threads.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdlib>
#include <random>
#include <vector>

#include "encoder/src/raster/projection_backward.h"
#include "encoder/src/raster/render_context.h"
#include "encoder/src/raster/splat_backward.h"
#include "encoder/src/raster/splat_renderer.h"
#include "sdk/src/layers/gaussian_set.h"
#include "sdk/src/layers/gaussian_views.h"
#include "sdk/src/render/camera.h"

namespace m4d {
namespace {

GaussianSet BoxScene(size_t n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  std::normal_distribution<float> normal(0.0f, 1.0f);
  GaussianSet set;
  set.sh_degree = 3;
  set.Resize(n);
  const float lo[3] = {-2.5f, -1.9f, 3.0f}, hi[3] = {2.5f, 1.9f, 8.0f};
  const float log_lo = std::log(0.015f), log_hi = std::log(0.08f);
  for (size_t i = 0; i < n; ++i) {
    for (int a = 0; a < 3; ++a) {
      set.positions[3 * i + a] = lo[a] + (hi[a] - lo[a]) * uniform(rng);
      set.log_scales[3 * i + a] = log_lo + (log_hi - log_lo) * uniform(rng);
    }
    for (int c = 0; c < 4; ++c) set.rotations[4 * i + c] = normal(rng);
    set.opacity_logits[i] = -1.5f + 3.0f * uniform(rng);
    for (int k = 0; k < 16; ++k) {
      for (int c = 0; c < 3; ++c) set.sh[48 * i + 3 * k + c] = (k == 0 ? 0.6f : 0.1f) * normal(rng);
    }
  }
  return set;
}

Camera BenchCamera(int width, int height) {
  Camera camera;
  camera.width = width;
  camera.height = height;
  camera.fx = camera.fy = static_cast<float>(width);
  camera.cx = 0.5f * width;
  camera.cy = 0.5f * height;
  return camera;
}

RenderSettings BenchSettings(int threads) {
  RenderSettings settings;
  settings.threads = threads;
  settings.sh_degree = 3;
  return settings;
}

void SetCounters(benchmark::State& state, const RenderContext& ctx) {
  size_t visible = 0;
  for (float r : ctx.splats.radius) visible += r > 0;
  state.counters["visible"] = static_cast<double>(visible);
  state.counters["tile_entries"] = static_cast<double>(ctx.bins.entries.size());
}

void BM_RasterForward(benchmark::State& state) {
  const Camera camera =
      BenchCamera(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  const GaussianSet set = BoxScene(static_cast<size_t>(state.range(2)), 1);
  const M4dGaussians view = GaussianView(set);
  const RenderSettings settings = BenchSettings(static_cast<int>(state.range(3)));
  RenderContext ctx;
  for (auto _ : state) {
    if (!RenderForward(camera, &view, 1, settings, nullptr, &ctx).ok()) std::abort();
    benchmark::DoNotOptimize(ctx.color.data());
  }
  SetCounters(state, ctx);
}

void BM_RasterForwardBackward(benchmark::State& state) {
  const Camera camera =
      BenchCamera(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  const size_t n = static_cast<size_t>(state.range(2));
  const GaussianSet set = BoxScene(n, 1);
  const M4dGaussians view = GaussianView(set);
  const RenderSettings settings = BenchSettings(static_cast<int>(state.range(3)));
  std::vector<float> dl_dcolor(3 * static_cast<size_t>(camera.width) * camera.height);
  std::mt19937 rng(2);
  std::uniform_real_distribution<float> uniform(-1.0f, 1.0f);
  for (float& v : dl_dcolor) v = uniform(rng);
  std::vector<float> positions(3 * n), log_scales(3 * n), rotations(4 * n), logits(n), sh(48 * n),
      mean2d(2 * n);
  LayerGradients layer;
  layer.positions = positions.data();
  layer.log_scales = log_scales.data();
  layer.rotations = rotations.data();
  layer.opacity_logits = logits.data();
  layer.sh = sh.data();
  SplatGradients out;
  out.layers = &layer;
  out.layer_count = 1;
  out.mean2d = mean2d.data();
  RenderContext ctx;
  BackwardWorkspace workspace;
  for (auto _ : state) {
    if (!RenderForward(camera, &view, 1, settings, nullptr, &ctx).ok()) std::abort();
    if (!RenderBackward(dl_dcolor.data(), nullptr, &ctx, out, &workspace).ok()) std::abort();
    benchmark::DoNotOptimize(positions.data());
  }
  SetCounters(state, ctx);
}

void RasterArgs(benchmark::internal::Benchmark* b) {
  for (int threads : {1, 2}) {
    b->Args({200, 150, 10000, threads});
    b->Args({200, 150, 100000, threads});
    b->Args({640, 480, 100000, threads});
  }
  b->ArgNames({"w", "h", "n", "threads"})->Unit(benchmark::kMillisecond)->UseRealTime();
}

BENCHMARK(BM_RasterForward)->Apply(RasterArgs);
BENCHMARK(BM_RasterForwardBackward)->Apply(RasterArgs);

}  // namespace
}  // namespace m4d
