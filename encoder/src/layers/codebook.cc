// Codebook fitting (bitstream-spec 5.4, version 0.6).
#include "encoder/src/layers/codebook.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <utility>
#include <vector>

namespace m4d {
namespace {

// Lloyd iterations: beyond this many, the index entropy and the PSNR of the default scene's
// keyframe hardly change (docs/results/2026-11-30-comment-measurements.md).
constexpr int kIterations = 12;

// The entry nearest to vector v (squared distance; the first of equals).
uint32_t Nearest(const float* v, const std::vector<float>& entries, int dims) {
  const size_t size = entries.size() / static_cast<size_t>(dims);
  float best = std::numeric_limits<float>::infinity();
  uint32_t best_k = 0;
  const float* e = entries.data();
  for (size_t k = 0; k < size; ++k, e += dims) {
    float d = 0.0f;
    for (int r = 0; r < dims && d < best; ++r) {
      const float x = v[r] - e[r];
      d += x * x;
    }
    if (d < best) {
      best = d;
      best_k = static_cast<uint32_t>(k);
    }
  }
  return best_k;
}

void Assign(const float* values, size_t n, size_t stride, int dims,
            const std::vector<float>& entries, std::vector<uint32_t>* index) {
  index->resize(n);
  for (size_t i = 0; i < n; ++i) (*index)[i] = Nearest(values + i * stride, entries, dims);
}

// Moves every entry to the mean of its vectors; an entry without any keeps its place.
void Update(const float* values, size_t n, size_t stride, int dims,
            const std::vector<uint32_t>& index, std::vector<float>* entries) {
  std::vector<double> sum(entries->size(), 0.0);
  std::vector<size_t> count(entries->size() / static_cast<size_t>(dims), 0);
  for (size_t i = 0; i < n; ++i) {
    const size_t k = index[i];
    ++count[k];
    for (int r = 0; r < dims; ++r) sum[k * dims + r] += values[i * stride + r];
  }
  for (size_t k = 0; k < count.size(); ++k) {
    if (count[k] == 0) continue;
    for (int r = 0; r < dims; ++r) {
      (*entries)[k * dims + r] = static_cast<float>(sum[k * dims + r] / count[k]);
    }
  }
}

// k-means++ seeding: each entry drawn with probability proportional to the squared distance to
// the nearest entry drawn so far, so that no cluster is left without an entry (uniform draws
// put two entries in one cluster of a test set of 40 and none in another: 3.6 times the error).
// The draws come from a fixed-seed mt19937, whose output is fixed by the C++ standard.
std::vector<float> SeedEntries(const float* values, size_t n, size_t stride, int dims, int size) {
  const size_t c = static_cast<size_t>(dims);
  std::vector<float> entries;
  entries.reserve(static_cast<size_t>(size) * c);
  std::mt19937 random(1);
  std::vector<double> nearest(n, std::numeric_limits<double>::infinity());
  size_t chosen = random() % n;
  for (int k = 0; k < size; ++k) {
    const float* e = values + chosen * stride;
    entries.insert(entries.end(), e, e + dims);
    double total = 0.0;
    for (size_t i = 0; i < n; ++i) {
      double d = 0.0;
      for (size_t r = 0; r < c; ++r) {
        const double x = static_cast<double>(values[i * stride + r]) - e[r];
        d += x * x;
      }
      nearest[i] = std::min(nearest[i], d);
      total += nearest[i];
    }
    if (!(total > 0.0)) break;  // fewer distinct vectors than entries: the rest stay unused
    double target = total * (static_cast<double>(random()) / 4294967296.0);
    chosen = n - 1;
    for (size_t i = 0; i < n; ++i) {
      target -= nearest[i];
      if (target < 0.0) {
        chosen = i;
        break;
      }
    }
  }
  // Entries never drawn repeat the first; no vector is nearer to them than to it.
  while (entries.size() < static_cast<size_t>(size) * c) {
    entries.insert(entries.end(), entries.begin(), entries.begin() + dims);
  }
  return entries;
}

// Morton code of an entry's first three components (bits interleaved from the most
// significant, component 0 first).
uint64_t MortonKey(const uint32_t* entry, int dims, int bits) {
  const int c = dims < 3 ? dims : 3;
  uint64_t key = 0;
  for (int b = bits - 1; b >= 0; --b) {
    for (int r = 0; r < c; ++r) key = (key << 1) | ((entry[r] >> b) & 1);
  }
  return key;
}

// Puts the entries in Morton order, so that similar entries get nearby indices: adaptive
// attributes (version 0.8) code an index given the top bits of the previous Gaussian's, which
// then say roughly where in colour space it lies (default scene's keyframe: 1.25 bits per
// Gaussian less for its 1024 SH DC entries).
void SortEntries(int dims, int bits, std::vector<uint32_t>* q, std::vector<float>* values) {
  const size_t c = static_cast<size_t>(dims);
  std::vector<uint32_t> order(q->size() / c);
  for (size_t k = 0; k < order.size(); ++k) order[k] = static_cast<uint32_t>(k);
  std::vector<uint64_t> keys(order.size());
  for (size_t k = 0; k < order.size(); ++k) keys[k] = MortonKey(&(*q)[k * c], dims, bits);
  std::stable_sort(order.begin(), order.end(),
                   [&keys](uint32_t a, uint32_t b) { return keys[a] < keys[b]; });
  std::vector<uint32_t> sorted_q(q->size());
  std::vector<float> sorted_values(values->size());
  for (size_t k = 0; k < order.size(); ++k) {
    for (size_t r = 0; r < c; ++r) {
      sorted_q[k * c + r] = (*q)[order[k] * c + r];
      sorted_values[k * c + r] = (*values)[order[k] * c + r];
    }
  }
  *q = std::move(sorted_q);
  *values = std::move(sorted_values);
}

}  // namespace

Codebook FitCodebook(const float* values, size_t n, size_t stride, int dims, int size,
                     const CodebookGrid& grid) {
  const size_t c = static_cast<size_t>(dims);
  std::vector<float> entries = SeedEntries(values, n, stride, dims, size);
  Codebook codebook;
  for (int iteration = 0; iteration < kIterations; ++iteration) {
    Assign(values, n, stride, dims, entries, &codebook.index);
    Update(values, n, stride, dims, codebook.index, &entries);
  }
  // Onto the grid, then the final assignment against the entries the decoder reconstructs.
  const double q_max = std::ldexp(1.0, grid.bits) - 1.0;
  codebook.entries.resize(entries.size());
  for (size_t k = 0; k < entries.size(); ++k) {
    const size_t r = k % c;
    const double x =
        grid.step[r] > 0.0f
            ? std::round((static_cast<double>(entries[k]) - grid.min[r]) / grid.step[r])
            : 0.0;
    codebook.entries[k] = static_cast<uint32_t>(std::min(std::max(x, 0.0), q_max));
    entries[k] = grid.min[r] + static_cast<float>(codebook.entries[k]) * grid.step[r];
  }
  SortEntries(dims, grid.bits, &codebook.entries, &entries);
  Assign(values, n, stride, dims, entries, &codebook.index);
  return codebook;
}

}  // namespace m4d
