// The training loss on RGB images of 200 x 150 and 640 x 480 (arg: width), on random content
// (a render against a noisy copy of it):
//   SsimValue:           zero-padded SSIM, value only.
//   SsimGradient:        zero-padded SSIM with its gradient (what training needs).
//   SsimValid:           the evaluation convention, value only.
//   PhotometricLoss:     L = 0.8 L1 + 0.2 (1 - SSIM) with dL/dimage, scratch reused.
//   Psnr:                for scale.
// Rows are split across all hardware threads.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdlib>
#include <random>
#include <vector>

#include "encoder/src/metrics/photometric_loss.h"
#include "encoder/src/metrics/psnr.h"
#include "encoder/src/metrics/ssim.h"

namespace m4d {
namespace {

struct ImagePair {
  Image rendered, target;
};

const ImagePair& Pair(int width) {
  static ImagePair pairs[2];
  ImagePair& pair = pairs[width == 200 ? 0 : 1];
  if (pair.rendered.width == 0) {
    const int height = width * 3 / 4;
    std::mt19937 rng(width);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    pair.rendered = Image(width, height, 3);
    pair.target = Image(width, height, 3);
    for (size_t i = 0; i < pair.rendered.pixels.size(); ++i) {
      pair.rendered.pixels[i] = unit(rng);
      pair.target.pixels[i] = 0.8f * pair.rendered.pixels[i] + 0.2f * unit(rng);
    }
  }
  return pair;
}

// With --benchmark_repetitions: the least disturbed run, for machines shared with other work.
double Min(const std::vector<double>& v) { return *std::min_element(v.begin(), v.end()); }

void SetPixels(benchmark::State& state, const ImagePair& pair) {
  state.SetItemsProcessed(state.iterations() * pair.rendered.width * pair.rendered.height);
}

void BM_SsimValue(benchmark::State& state) {
  const ImagePair& pair = Pair(static_cast<int>(state.range(0)));
  SsimWorkspace workspace;
  double ssim = 0;
  for (auto _ : state) {
    if (!SsimZeroPadded(pair.rendered, pair.target, &ssim, nullptr, &workspace).ok()) std::abort();
    benchmark::DoNotOptimize(ssim);
  }
  SetPixels(state, pair);
}

void BM_SsimGradient(benchmark::State& state) {
  const ImagePair& pair = Pair(static_cast<int>(state.range(0)));
  SsimWorkspace workspace;
  Image grad;
  double ssim = 0;
  for (auto _ : state) {
    if (!SsimZeroPadded(pair.rendered, pair.target, &ssim, &grad, &workspace).ok()) std::abort();
    benchmark::DoNotOptimize(grad.pixels.data());
  }
  SetPixels(state, pair);
}

void BM_SsimValid(benchmark::State& state) {
  const ImagePair& pair = Pair(static_cast<int>(state.range(0)));
  SsimWorkspace workspace;
  double ssim = 0;
  for (auto _ : state) {
    if (!SsimValid(pair.rendered, pair.target, &ssim, &workspace).ok()) std::abort();
    benchmark::DoNotOptimize(ssim);
  }
  SetPixels(state, pair);
}

void BM_PhotometricLoss(benchmark::State& state) {
  const ImagePair& pair = Pair(static_cast<int>(state.range(0)));
  PhotometricLoss loss;
  PhotometricLossValue value;
  Image grad;
  for (auto _ : state) {
    if (!loss.Evaluate(pair.rendered, pair.target, &value, &grad).ok()) std::abort();
    benchmark::DoNotOptimize(grad.pixels.data());
  }
  SetPixels(state, pair);
}

void BM_Psnr(benchmark::State& state) {
  const ImagePair& pair = Pair(static_cast<int>(state.range(0)));
  double psnr = 0;
  for (auto _ : state) {
    if (!Psnr(pair.rendered, pair.target, &psnr).ok()) std::abort();
    benchmark::DoNotOptimize(psnr);
  }
  SetPixels(state, pair);
}

#define M4D_METRICS_BENCHMARK(name)   \
  BENCHMARK(name)                     \
      ->Arg(200)                      \
      ->Arg(640)                      \
      ->Unit(benchmark::kMillisecond) \
      ->UseRealTime()                 \
      ->ComputeStatistics("min", Min)

M4D_METRICS_BENCHMARK(BM_SsimValue);
M4D_METRICS_BENCHMARK(BM_SsimGradient);
M4D_METRICS_BENCHMARK(BM_SsimValid);
M4D_METRICS_BENCHMARK(BM_PhotometricLoss);
M4D_METRICS_BENCHMARK(BM_Psnr);

}  // namespace
}  // namespace m4d
