#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <ctime>
#include <random>
#include <vector>

#include "encoder/src/entropy/symbol_block_writer.h"
#include "sdk/src/common/byte_reader.h"
#include "sdk/src/common/byte_writer.h"
#include "sdk/src/common/crc32.h"
#include "sdk/src/common/md5.h"
#include "sdk/src/entropy/symbol_block_reader.h"

namespace m4d {
namespace {

// Values of the motion grid of the paper's configuration: 32^3*4 + 64^3*4 + 128^3*2.
constexpr size_t kGridValues = 5373952;

std::vector<int32_t> Laplacian(size_t count, double scale, uint32_t seed) {
  std::mt19937 rng(seed);
  std::exponential_distribution<double> magnitude(1.0 / scale);
  std::vector<int32_t> values(count);
  for (auto& v : values) {
    const int32_t m = static_cast<int32_t>(std::min(magnitude(rng) + 0.5, 2047.0));
    v = rng() & 1 ? m : -m;
  }
  return values;
}

std::vector<int32_t> MostlyZero(size_t count, uint32_t seed) {
  std::mt19937 rng(seed);
  std::bernoulli_distribution nonzero(0.05);
  std::vector<int32_t> values = Laplacian(count, 4.0, seed + 1);
  for (auto& v : values) {
    if (!nonzero(rng)) v = 0;
  }
  return values;
}

std::vector<uint8_t> Encode(const std::vector<int32_t>& values) {
  std::vector<uint8_t> bytes;
  ByteWriter writer(&bytes);
  if (!WriteSymbolBlock(values.data(), values.size(), RansLayout::kInterleaved, &writer).ok())
    std::abort();
  return bytes;
}

// CPU time of this thread in nanoseconds, the clock the library's own times use.
double ThreadCpuNs() {
  timespec t;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return t.tv_sec * 1e9 + t.tv_nsec;
}

// An inverted rate counter would do, but prints seconds; this one prints plain ns/symbol.
void SetNsPerSymbol(benchmark::State& state, double elapsed_ns, size_t count) {
  state.counters["ns_per_symbol"] = elapsed_ns / (static_cast<double>(state.iterations()) * count);
}

void DecodeBenchmark(benchmark::State& state, const std::vector<int32_t>& values) {
  const std::vector<uint8_t> bytes = Encode(values);
  std::vector<int32_t> out(values.size());
  const uint32_t count = static_cast<uint32_t>(values.size());
  const double start = ThreadCpuNs();
  for (auto _ : state) {
    ByteReader reader(bytes.data(), bytes.size());
    if (!ReadSymbolBlock(&reader, RansLayout::kInterleaved, count, -4096, 4096, out.data()).ok()) {
      state.SkipWithError("decode failed");
      break;
    }
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
  }
  SetNsPerSymbol(state, ThreadCpuNs() - start, values.size());
  if (out != values) state.SkipWithError("decode mismatch");
  state.counters["bits_per_symbol"] = 8.0 * bytes.size() / values.size();
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * values.size()));
}

void BM_DecodeLaplacian1M(benchmark::State& state) {
  DecodeBenchmark(state, Laplacian(1000000, 3.0, 1));
}
BENCHMARK(BM_DecodeLaplacian1M)->Unit(benchmark::kMillisecond);

void BM_DecodeMostlyZeroGrid(benchmark::State& state) {
  DecodeBenchmark(state, MostlyZero(kGridValues, 2));
}
BENCHMARK(BM_DecodeMostlyZeroGrid)->Unit(benchmark::kMillisecond);

// Small blocks (MLP layers, brick flags): table set-up dominates.
void BM_DecodeSmall(benchmark::State& state) {
  DecodeBenchmark(state, Laplacian(static_cast<size_t>(state.range(0)), 3.0, 3));
}
BENCHMARK(BM_DecodeSmall)->RangeMultiplier(4)->Range(16, 16384);

void BM_EncodeLaplacian1M(benchmark::State& state) {
  const std::vector<int32_t> values = Laplacian(1000000, 3.0, 1);
  std::vector<uint8_t> bytes;
  const double start = ThreadCpuNs();
  for (auto _ : state) {
    bytes.clear();
    ByteWriter writer(&bytes);
    benchmark::DoNotOptimize(
        WriteSymbolBlock(values.data(), values.size(), RansLayout::kInterleaved, &writer));
  }
  SetNsPerSymbol(state, ThreadCpuNs() - start, values.size());
}
BENCHMARK(BM_EncodeLaplacian1M)->Unit(benchmark::kMillisecond);

std::vector<uint8_t> RandomBytes(size_t size) {
  std::mt19937 rng(4);
  std::vector<uint8_t> data(size);
  for (auto& b : data) b = static_cast<uint8_t>(rng());
  return data;
}

void BM_Crc32_1MiB(benchmark::State& state) {
  const std::vector<uint8_t> data = RandomBytes(1 << 20);
  for (auto _ : state) benchmark::DoNotOptimize(Crc32(data.data(), data.size()));
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations() * data.size()));
}
BENCHMARK(BM_Crc32_1MiB);

void BM_Md5_1MiB(benchmark::State& state) {
  const std::vector<uint8_t> data = RandomBytes(1 << 20);
  uint8_t digest[16];
  for (auto _ : state) {
    Md5 md5;
    md5.Update(data.data(), data.size());
    md5.Final(digest);
    benchmark::DoNotOptimize(digest);
  }
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations() * data.size()));
}
BENCHMARK(BM_Md5_1MiB);

}  // namespace
}  // namespace m4d
