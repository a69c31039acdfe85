// Keyframe training (encoder/src/train):
//   TrainIteration:    one full iteration of KeyframeTrainer::Step (render, loss with its
//                      gradient, rasterizer backward, Adam over every parameter; no
//                      densification) with SH degree 3 active.
//   AdamStep:          the Adam step alone over n Gaussians (59 floats each).
//   NearestNeighbours: kd-tree build plus 3 nearest neighbours of every point (the
//                      initialisation's scale) for n points uniform in a box.
// Scene: the rasterizer benchmark's box of Gaussians (Gaussians uniformly in
// [-2.5, 2.5] x [-1.9, 1.9] x [3, 8], scales 0.015 to 0.08, SH degree 3) seen by 4 cameras
// near the origin looking down +z; the target images are renders of another draw of the
// same distribution, so that the loss and its gradients are not trivial.
// Arguments: width, height, Gaussian count, threads.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdlib>
#include <random>
#include <utility>
#include <vector>

#include "encoder/src/geometry/nearest_neighbours.h"
#include "encoder/src/raster/splat_renderer.h"
#include "encoder/src/train/gaussian_model.h"
#include "encoder/src/train/gaussian_optimizer.h"
#include "encoder/src/train/keyframe_trainer.h"
#include "sdk/src/layers/gaussian_set.h"

namespace m4d {
namespace {

GaussianModel BoxModel(size_t n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  std::normal_distribution<float> normal(0.0f, 1.0f);
  GaussianModel model;
  model.Resize(n);
  const float lo[3] = {-2.5f, -1.9f, 3.0f}, hi[3] = {2.5f, 1.9f, 8.0f};
  const float log_lo = std::log(0.015f), log_hi = std::log(0.08f);
  for (size_t i = 0; i < n; ++i) {
    for (int a = 0; a < 3; ++a) {
      model.positions[3 * i + a] = lo[a] + (hi[a] - lo[a]) * uniform(rng);
      model.log_scales[3 * i + a] = log_lo + (log_hi - log_lo) * uniform(rng);
    }
    for (int c = 0; c < 4; ++c) model.rotations[4 * i + c] = normal(rng);
    model.opacity_logits[i] = -1.5f + 3.0f * uniform(rng);
    for (int k = 0; k < 48; ++k) model.sh[48 * i + k] = (k < 3 ? 0.6f : 0.1f) * normal(rng);
  }
  return model;
}

TrainingViews BoxViews(int width, int height, const GaussianModel& truth) {
  TrainingViews views;
  RenderSettings settings;
  RenderContext context;
  const M4dGaussians layer = GaussianView(truth);
  for (int v = 0; v < 4; ++v) {
    Camera camera;
    camera.width = width;
    camera.height = height;
    camera.fx = camera.fy = static_cast<float>(width);
    camera.cx = 0.5f * width;
    camera.cy = 0.5f * height;
    camera.translation[0] = 0.1f * (v - 1.5f);
    if (!RenderForward(camera, &layer, 1, settings, nullptr, &context).ok()) std::abort();
    Image image(width, height, 3);
    for (size_t i = 0; i < image.pixels.size(); ++i) {
      image.pixels[i] = std::fmin(std::fmax(context.color[i], 0.0f), 1.0f);
    }
    views.camera_indices.push_back(v);
    views.cameras.push_back(camera);
    views.images.push_back(std::move(image));
  }
  return views;
}

void BM_TrainIteration(benchmark::State& state) {
  const int width = static_cast<int>(state.range(0)), height = static_cast<int>(state.range(1));
  const size_t n = static_cast<size_t>(state.range(2));
  KeyframeTrainingOptions options;
  options.densify_until = 0;
  options.start_sh_degree = 3;
  options.scene_extent = 5.0f;
  options.context.threads = static_cast<int>(state.range(3));
  KeyframeTrainer trainer;
  if (!trainer.Init(options, BoxViews(width, height, BoxModel(n, 2)), BoxModel(n, 1)).ok()) {
    std::abort();
  }
  for (auto _ : state) {
    if (!trainer.Step().ok()) std::abort();
  }
  state.counters["loss"] = trainer.last_loss().loss;
}

void BM_AdamStep(benchmark::State& state) {
  const size_t n = static_cast<size_t>(state.range(0));
  GaussianModel model = BoxModel(n, 1);
  const GaussianModel gradients = BoxModel(n, 2);
  AdamOptimizer adam = MakeGaussianOptimizer(model, GaussianLearningRates(), 5.0f);
  ThreadPool pool(static_cast<int>(state.range(1)));
  for (auto _ : state) {
    StepGaussianOptimizer(gradients, kGaussianParameterCount, &adam, &model, &pool);
    benchmark::DoNotOptimize(model.positions.data());
  }
}

void BM_NearestNeighbours(benchmark::State& state) {
  const size_t n = static_cast<size_t>(state.range(0));
  const GaussianModel model = BoxModel(n, 1);
  std::vector<uint32_t> indices(3 * n);
  std::vector<float> d2(3 * n);
  for (auto _ : state) {
    NearestNeighbours knn;
    if (!knn.Build(model.positions.data(), n).ok()) std::abort();
    knn.QueryAll(model.positions.data(), n, 3, true, static_cast<int>(state.range(1)),
                 indices.data(), d2.data());
    benchmark::DoNotOptimize(d2.data());
  }
}

void TrainArgs(benchmark::internal::Benchmark* b) {
  for (int threads : {1, 2}) {
    b->Args({200, 150, 10000, threads});
    b->Args({200, 150, 100000, threads});
  }
  b->ArgNames({"w", "h", "n", "threads"})->Unit(benchmark::kMillisecond)->UseRealTime();
}

void CountArgs(benchmark::internal::Benchmark* b) {
  for (int threads : {1, 2}) b->Args({100000, threads});
  b->Args({1000000, 2});
  b->ArgNames({"n", "threads"})->Unit(benchmark::kMillisecond)->UseRealTime();
}

BENCHMARK(BM_TrainIteration)->Apply(TrainArgs);
BENCHMARK(BM_AdamStep)->Apply(CountArgs);
BENCHMARK(BM_NearestNeighbours)->Apply(CountArgs);

}  // namespace
}  // namespace m4d
