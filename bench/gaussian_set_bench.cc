// gaussian_set() coding (bitstream-spec 5.4, 5.5) of a keyframe layer: 100k Gaussians on
// surfaces, with colours that vary smoothly over them, at SH degree 3 and 0. Decoding
// (ReadGaussianSet) should stay under 100 ms on one thread.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <random>
#include <vector>

#include "encoder/src/layers/gaussian_set_writer.h"
#include "sdk/src/common/byte_reader.h"
#include "sdk/src/common/byte_writer.h"
#include "sdk/src/common/spec_limits.h"
#include "sdk/src/layers/gaussian_set_reader.h"

namespace m4d {
namespace {

constexpr size_t kGaussians = 100000;

// Gaussians on 60 ellipsoid shells (a scene's surfaces), flat along the shell, mostly opaque,
// base colour a smooth function of position and view-dependent terms shrinking with degree.
GaussianSet SurfaceSet(size_t n, int sh_degree, uint32_t seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<float> normal(0, 1);
  std::uniform_real_distribution<float> uniform(0, 1);
  struct Shell {
    float center[3], radius[3];
  };
  std::vector<Shell> shells(60);
  for (Shell& s : shells) {
    for (int a = 0; a < 3; ++a) {
      s.center[a] = 8 * (uniform(rng) - 0.5f);
      s.radius[a] = 0.2f + uniform(rng);
    }
  }
  GaussianSet set;
  set.sh_degree = sh_degree;
  set.Resize(n);
  const int k_count = ShCoefficients(sh_degree);
  for (size_t i = 0; i < n; ++i) {
    const Shell& s = shells[rng() % shells.size()];
    float d[3] = {normal(rng), normal(rng), normal(rng)};
    const float len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) + 1e-6f;
    float* p = &set.positions[3 * i];
    for (int a = 0; a < 3; ++a) p[a] = s.center[a] + s.radius[a] * d[a] / len + 0.01f * normal(rng);
    const float size = -4.5f + 0.6f * normal(rng);
    for (int a = 0; a < 3; ++a) {
      set.log_scales[3 * i + a] = size + 0.3f * normal(rng) - (a == 2 ? 1.5f : 0.0f);
    }
    float q[4], norm = 0;
    for (float& c : q) {
      c = normal(rng);
      norm += c * c;
    }
    const float scale = (0.8f + 0.4f * uniform(rng)) / std::sqrt(norm);
    for (int c = 0; c < 4; ++c) set.rotations[4 * i + c] = q[c] * scale;
    set.opacity_logits[i] = uniform(rng) < 0.6f ? 4 + 1.5f * normal(rng) : -2 + 2 * normal(rng);
    float* sh = &set.sh[static_cast<size_t>(3 * k_count) * i];
    for (int k = 0; k < k_count; ++k) {
      const float amplitude = k == 0 ? 1.5f : 0.25f / (1 + std::sqrt(static_cast<float>(k)));
      for (int c = 0; c < 3; ++c) {
        const float smooth = std::sin(0.7f * p[0] + c + k) * std::cos(0.5f * p[1] - k) +
                             0.3f * std::sin(p[2] * (1 + c));
        sh[3 * k + c] = amplitude * smooth + (k == 0 ? 0.1f : 0.05f) * normal(rng);
      }
    }
  }
  return set;
}

// With `codebooks`, SH DC and higher SH are coded with 1024 and 256 entries (bitstream 0.6),
// kept whether or not they pay on this content.
std::vector<uint8_t> Encode(const GaussianSet& set, bool codebooks = false) {
  std::vector<uint8_t> bytes;
  ByteWriter writer(&bytes);
  GaussianQuantization q;
  if (codebooks) {
    q.sh_dc_codebook = 1024;
    q.sh_rest_codebook = 256;
    q.codebooks_only_where_they_pay = false;
  }
  if (!WriteGaussianSet(set, q, &writer).ok()) std::abort();
  return bytes;
}

void SetBytesPerGaussian(benchmark::State& state, size_t bytes) {
  state.counters["bytes_per_gaussian"] = static_cast<double>(bytes) / kGaussians;
}

void BM_ReadGaussianSet(benchmark::State& state) {
  const int sh_degree = static_cast<int>(state.range(0));
  const std::vector<uint8_t> bytes =
      Encode(SurfaceSet(kGaussians, sh_degree, 1), state.range(1) != 0);
  for (auto _ : state) {
    ByteReader reader(bytes.data(), bytes.size());
    GaussianSet set;
    if (!ReadGaussianSet(&reader, sh_degree, GaussianSetSyntax(), kMaxGaussiansPerSet, &set).ok())
      std::abort();
    benchmark::DoNotOptimize(set.sh.data());
  }
  SetBytesPerGaussian(state, bytes.size());
}
// Arguments: SH degree, codebooks.
BENCHMARK(BM_ReadGaussianSet)
    ->Args({3, 0})
    ->Args({0, 0})
    ->Args({3, 1})
    ->Args({1, 1})
    ->Unit(benchmark::kMillisecond);

void BM_WriteGaussianSet(benchmark::State& state) {
  const GaussianSet set = SurfaceSet(kGaussians, static_cast<int>(state.range(0)), 1);
  size_t size = 0;
  for (auto _ : state) {
    const std::vector<uint8_t> bytes = Encode(set);
    size = bytes.size();
    benchmark::DoNotOptimize(bytes.data());
  }
  SetBytesPerGaussian(state, size);
}
BENCHMARK(BM_WriteGaussianSet)->Arg(3)->Arg(0)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace m4d
