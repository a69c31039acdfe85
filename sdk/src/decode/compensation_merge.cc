#include "sdk/src/decode/compensation_merge.h"

#include <cstring>

namespace m4d {
namespace {

// Copies row `from` of `src` to row `to` of `dst` for every attribute.
void CopyRow(const GaussianSet& src, size_t from, GaussianSet* dst, size_t to) {
  const auto copy = [](const Buffer<float>& s, size_t width, size_t i, Buffer<float>* d, size_t j) {
    std::memmove(&(*d)[j * width], &s[i * width], width * sizeof(float));
  };
  copy(src.positions, 3, from, &dst->positions, to);
  copy(src.log_scales, 3, from, &dst->log_scales, to);
  copy(src.rotations, 4, from, &dst->rotations, to);
  copy(src.opacity_logits, 1, from, &dst->opacity_logits, to);
  copy(src.sh, static_cast<size_t>(src.sh_floats()), from, &dst->sh, to);
}

}  // namespace

void MergeCompensation(const int32_t* removed, const GaussianSet& added, GaussianSet* set) {
  const size_t n = set->size();
  const size_t m = added.size();
  // Added Gaussians fill the holes in increasing order.
  size_t i = 0, filled = 0;
  for (; removed != nullptr && i < n && filled < m; ++i) {
    if (removed[i]) CopyRow(added, filled++, set, i);
  }
  if (filled < m) {  // every hole is filled: the rest is appended
    set->Resize(n + m - filled);
    for (size_t j = filled; j < m; ++j) CopyRow(added, j, set, n + j - filled);
    return;
  }
  // Holes left from index i on: the last Gaussian moves into each, largest hole first, so it
  // never moves into a hole still to be filled.
  size_t count = n;
  for (size_t k = n; removed != nullptr && k-- > i;) {
    if (!removed[k]) continue;
    if (k != count - 1) CopyRow(*set, count - 1, set, k);
    --count;
  }
  set->Resize(count);
}

}  // namespace m4d
