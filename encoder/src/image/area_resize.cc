#include "encoder/src/image/area_resize.h"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace m4d {
namespace {

// Input samples and weights of each output sample along one axis.
struct AxisTaps {
  std::vector<int> first;      // first input index, per output index
  std::vector<size_t> offset;  // start in `weights`, per output index, plus the end
  std::vector<float> weights;
};

// Output pixel o covers input [o * in / out, (o + 1) * in / out). In units of 1 / out the
// bounds are the integers o * in and (o + 1) * in and input pixel i is [i * out, (i + 1) *
// out), so the overlaps are exact integers and the weights (overlap / in) sum to 1.
AxisTaps AreaTaps(int in_size, int out_size) {
  AxisTaps taps;
  const int64_t in = in_size, out = out_size;
  for (int64_t o = 0; o < out; ++o) {
    const int64_t lo = o * in, hi = (o + 1) * in;
    taps.first.push_back(static_cast<int>(lo / out));
    taps.offset.push_back(taps.weights.size());
    for (int64_t i = lo / out; i * out < hi; ++i) {
      const int64_t overlap = std::min(hi, (i + 1) * out) - std::max(lo, i * out);
      taps.weights.push_back(static_cast<float>(static_cast<double>(overlap) / in));
    }
  }
  taps.offset.push_back(taps.weights.size());
  return taps;
}

void ResizeRows(const Image& in, const AxisTaps& taps, Image* out) {
  const int c = in.channels;
  for (int y = 0; y < in.height; ++y) {
    const float* src = in.row(y);
    float* dst = out->row(y);
    for (int x = 0; x < out->width; ++x) {
      float sum[4] = {0, 0, 0, 0};
      const float* s = src + static_cast<size_t>(taps.first[x]) * c;
      for (size_t k = taps.offset[x]; k < taps.offset[x + 1]; ++k, s += c) {
        for (int ch = 0; ch < c; ++ch) sum[ch] += taps.weights[k] * s[ch];
      }
      std::copy_n(sum, c, dst + static_cast<size_t>(x) * c);
    }
  }
}

void ResizeColumns(const Image& in, const AxisTaps& taps, Image* out) {
  const size_t n = in.row_size();
  for (int y = 0; y < out->height; ++y) {
    float* dst = out->row(y);
    std::fill(dst, dst + n, 0.0f);
    int src_y = taps.first[y];
    for (size_t k = taps.offset[y]; k < taps.offset[y + 1]; ++k, ++src_y) {
      const float w = taps.weights[k];
      const float* src = in.row(src_y);
      for (size_t i = 0; i < n; ++i) dst[i] += w * src[i];
    }
  }
}

}  // namespace

Status ResizeArea(const Image& in, int width, int height, Image* out) {
  M4D_RETURN_IF_ERROR(CheckImage(in, "resize input"));
  M4D_RETURN_IF_ERROR(CheckImageShape(width, in.height, in.channels, "resize intermediate"));
  M4D_RETURN_IF_ERROR(CheckImageShape(width, height, in.channels, "resize output"));
  Image rows(width, in.height, in.channels);
  ResizeRows(in, AreaTaps(in.width, width), &rows);
  Reshape(width, height, in.channels, out);
  ResizeColumns(rows, AreaTaps(in.height, height), out);
  return Status::Ok();
}

}  // namespace m4d
