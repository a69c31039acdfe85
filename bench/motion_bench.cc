// The motion part of an inter-frame decode, single thread, paper configuration (grid
// 4x32^3 + 4x64^3 + 2x128^3, MLP 10 -> 64 -> 7):
//   ReadMotionGrid:  one MOTION_GRID payload whose motion is a smooth blob filling ~5% of the
//                    box, quantized with step 1/64 (most voxels 0).
//   ApplyMotion:     100k Gaussians; arg 0: uniform in the box, in spatial (Morton) order as
//                    Draco's kd-tree returns them (the most grid memory touched); arg 1: the
//                    same in random order (worst case for the caches); arg 2: on a sphere
//                    like the surface of a captured object, spatial order. Second arg: the
//                    kernel build (0 baseline AVX2, 1 AVX-512).
//   MotionFrame:     grid read and arg 0, as one inter frame does them.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "encoder/src/layers/mlp_weights_writer.h"
#include "encoder/src/layers/motion_grid_writer.h"
#include "sdk/src/common/byte_reader.h"
#include "sdk/src/common/byte_writer.h"
#include "sdk/src/decode/motion_application.h"
#include "sdk/src/layers/gaussian_set.h"
#include "sdk/src/layers/mlp_weights.h"
#include "sdk/src/layers/motion_grid.h"

namespace m4d {
namespace {

constexpr size_t kGaussians = 100000;
enum SetKind { kUniformSpatial, kUniformRandom, kShellSpatial };

// A blob of radius 0.23 (5% of the unit box) around (0.4, 0.55, 0.5) in box coordinates.
constexpr float kBlobCenter[3] = {0.4f, 0.55f, 0.5f};
constexpr float kBlobRadius = 0.23f;

struct MotionData {
  GridConfig config;  // the paper's by default
  std::vector<uint8_t> grid_payload;
  MotionGrid grid;
  MlpWeights mlp;
  GaussianSet sets[3];
};

std::vector<uint8_t> BlobGridPayload(const GridConfig& config) {
  FloatMotionGrid grid;
  for (int a = 0; a < 3; ++a) {
    grid.box_min[a] = -1.0f;
    grid.box_scale[a] = 0.5f;
  }
  for (int l = 0; l < config.num_levels; ++l) {
    const int r = config.resolution[l], c = config.channels[l];
    grid.values[l].assign(config.level_values(l), 0.0f);
    for (int z = 0; z < r; ++z) {
      for (int y = 0; y < r; ++y) {
        for (int x = 0; x < r; ++x) {
          const float p[3] = {x / (r - 1.0f), y / (r - 1.0f), z / (r - 1.0f)};
          float d2 = 0;
          for (int a = 0; a < 3; ++a) d2 += (p[a] - kBlobCenter[a]) * (p[a] - kBlobCenter[a]);
          const float s = 1.0f - d2 / (kBlobRadius * kBlobRadius);
          if (s <= 0) continue;
          for (int ch = 0; ch < c; ++ch) {
            grid.values[l][((static_cast<size_t>(z) * r + y) * r + x) * c + ch] =
                0.3f * s * s * std::sin(6.0f * p[ch % 3] + static_cast<float>(ch + l));
          }
        }
      }
    }
  }
  std::vector<uint8_t> payload;
  ByteWriter writer(&payload);
  if (!WriteMotionGrid(config, grid, RansLayout::kInterleaved, &writer).ok()) std::abort();
  return payload;
}

uint32_t Spread3(uint32_t v) {
  uint32_t r = 0;
  for (int b = 0; b < 10; ++b) r |= ((v >> b) & 1u) << (3 * b);
  return r;
}

// Sorts box coordinates by their Morton code on a 1024^3 lattice: a spatially coherent order
// like the one Draco's kd-tree coder returns.
std::vector<float> SpatialOrder(const std::vector<float>& u) {
  const size_t n = u.size() / 3;
  std::vector<std::pair<uint32_t, size_t>> keys(n);
  for (size_t i = 0; i < n; ++i) {
    uint32_t key = 0;
    for (int a = 0; a < 3; ++a) {
      key |= Spread3(std::min(static_cast<uint32_t>(u[3 * i + a] * 1024), 1023u)) << a;
    }
    keys[i] = {key, i};
  }
  std::sort(keys.begin(), keys.end());
  std::vector<float> sorted(u.size());
  for (size_t i = 0; i < n; ++i) std::copy_n(&u[3 * keys[i].second], 3, &sorted[3 * i]);
  return sorted;
}

// A set at the given box coordinates, with random rotations.
GaussianSet MakeSet(const MotionGrid& grid, const std::vector<float>& u, std::mt19937* rng) {
  GaussianSet set;
  set.Resize(u.size() / 3);
  for (size_t i = 0; i < u.size(); ++i) {
    set.positions[i] = grid.box_min[i % 3] + u[i] / grid.box_scale[i % 3];
  }
  std::normal_distribution<float> normal(0.0f, 1.0f);
  for (float& q : set.rotations) q = normal(*rng);
  return set;
}

const MotionData& Data() {
  static const MotionData* data = [] {
    auto* d = new MotionData;
    d->grid_payload = BlobGridPayload(d->config);
    ByteReader reader(d->grid_payload.data(), d->grid_payload.size());
    if (!ReadMotionGrid(&reader, RansLayout::kInterleaved, d->config, &d->grid).ok()) std::abort();

    // The MLP as decoded: random weights of a 10 -> 64 -> 7 network through the 12-bit writer.
    std::mt19937 rng(1);
    MlpWeights mlp;
    mlp.layers = MlpShapes(d->config.feature_count(), MlpConfig{});
    std::normal_distribution<float> normal(0.0f, 0.2f);
    for (MlpLayer& layer : mlp.layers) {
      for (float& w : layer.weights) w = normal(rng);
      for (float& b : layer.biases) b = 0.1f * normal(rng);
    }
    std::vector<uint8_t> payload;
    ByteWriter writer(&payload);
    if (!WriteMlpWeights(mlp, 12, RansLayout::kInterleaved, &writer).ok()) std::abort();
    ByteReader mlp_reader(payload.data(), payload.size());
    if (!ReadMlpWeights(&mlp_reader, RansLayout::kInterleaved, d->config.feature_count(),
                        MlpConfig{}, &d->mlp)
             .ok()) {
      std::abort();
    }

    // Box coordinates of the Gaussians: uniform in the box, or on a sphere like the surface
    // of a captured object.
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    std::normal_distribution<float> normal3(0.0f, 1.0f);
    std::vector<float> uniform(3 * kGaussians), shell(3 * kGaussians);
    for (size_t i = 0; i < kGaussians; ++i) {
      float v[3], norm = 0;
      for (int a = 0; a < 3; ++a) {
        uniform[3 * i + a] = unit(rng);
        v[a] = normal3(rng);
        norm += v[a] * v[a];
      }
      const float radius = (0.35f + 0.01f * unit(rng)) / std::sqrt(norm);
      for (int a = 0; a < 3; ++a) shell[3 * i + a] = 0.5f + radius * v[a];
    }
    d->sets[kUniformSpatial] = MakeSet(d->grid, SpatialOrder(uniform), &rng);
    d->sets[kUniformRandom] = MakeSet(d->grid, uniform, &rng);
    d->sets[kShellSpatial] = MakeSet(d->grid, SpatialOrder(shell), &rng);
    return d;
  }();
  return *data;
}

// With --benchmark_repetitions: the least disturbed run, for machines shared with other work.
double Min(const std::vector<double>& v) { return *std::min_element(v.begin(), v.end()); }

void ReadGrid(const MotionData& data, MotionGrid* grid) {
  ByteReader reader(data.grid_payload.data(), data.grid_payload.size());
  if (!ReadMotionGrid(&reader, RansLayout::kInterleaved, data.config, grid).ok()) std::abort();
}

void BM_ReadMotionGrid(benchmark::State& state) {
  const MotionData& data = Data();
  MotionGrid grid;
  for (auto _ : state) {
    ReadGrid(data, &grid);
    benchmark::DoNotOptimize(grid.values[2].data());
  }
  state.counters["payload_bytes"] = static_cast<double>(data.grid_payload.size());
}
BENCHMARK(BM_ReadMotionGrid)->Unit(benchmark::kMillisecond)->ComputeStatistics("min", Min);

// Every iteration moves a fresh copy of the set (the copy is not timed). Arg 1 is the kernel
// (MotionKernelKind: 0 baseline, 1 AVX-512).
void BM_ApplyMotion(benchmark::State& state) {
  const MotionData& data = Data();
  const GaussianSet& original = data.sets[state.range(0)];
  const auto kind = static_cast<MotionKernelKind>(state.range(1));
  if (!MotionKernelSupported(kind)) {
    state.SkipWithError("kernel not supported by this build or CPU");
    return;
  }
  GaussianSet set = original;
  for (auto _ : state) {
    state.PauseTiming();
    set = original;
    state.ResumeTiming();
    ApplyMotionWith(kind, data.config, data.grid, data.mlp, &set);
    benchmark::DoNotOptimize(set.positions.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(kGaussians));
}
BENCHMARK(BM_ApplyMotion)
    ->ArgsProduct({{kUniformSpatial, kUniformRandom, kShellSpatial}, {0, 1}})
    ->Unit(benchmark::kMillisecond)
    ->ComputeStatistics("min", Min);

void BM_MotionFrame(benchmark::State& state) {
  const MotionData& data = Data();
  MotionGrid grid;
  const GaussianSet& original = data.sets[kUniformSpatial];
  GaussianSet set = original;
  for (auto _ : state) {
    state.PauseTiming();
    set = original;
    state.ResumeTiming();
    ReadGrid(data, &grid);
    ApplyMotion(data.config, grid, data.mlp, &set);
    benchmark::DoNotOptimize(set.positions.data());
  }
}
BENCHMARK(BM_MotionFrame)->Unit(benchmark::kMillisecond)->ComputeStatistics("min", Min);

}  // namespace
}  // namespace m4d
