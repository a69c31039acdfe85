// Codebook fitting (bitstream-spec 5.4, version 0.6).
#include "layers/codebook.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace m4d {
namespace {

// Lloyd iterations: the index entropy and the PSNR of the default scene's keyframe change by
// less than 0.01 bits and 0.01 dB beyond this many.
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
  Assign(values, n, stride, dims, entries, &codebook.index);
  return codebook;
}

}  // namespace m4d
