#include "encoder/src/metrics/gaussian_filter.h"

#include <cmath>

namespace m4d {
namespace {

std::array<float, kGaussianTaps> MakeWindow() {
  double w[kGaussianTaps], sum = 0;
  for (int k = 0; k < kGaussianTaps; ++k) {
    const double d = k - kGaussianRadius;
    w[k] = std::exp(-d * d / (2 * kGaussianSigma * kGaussianSigma));
    sum += w[k];
  }
  std::array<float, kGaussianTaps> g;
  for (int k = 0; k < kGaussianTaps; ++k) g[k] = static_cast<float>(w[k] / sum);
  return g;
}

}  // namespace

const std::array<float, kGaussianTaps>& GaussianWindow() {
  static const std::array<float, kGaussianTaps> window = MakeWindow();
  return window;
}

// The taps unroll and i vectorizes.
void FilterPaddedRow(const float* __restrict padded, int width, int channels,
                     float* __restrict out) {
  const std::array<float, kGaussianTaps>& g = GaussianWindow();
  const size_t stride = static_cast<size_t>(channels);
  const size_t n = static_cast<size_t>(width) * channels;
  for (size_t i = 0; i < n; ++i) {
    float sum = 0.0f;
    for (int k = 0; k < kGaussianTaps; ++k) sum += g[k] * padded[i + k * stride];
    out[i] = sum;
  }
}

void GatherWindowRows(const float* image, size_t row_size, int height, int y, const float* zeros,
                      const float* rows[kGaussianTaps]) {
  for (int k = 0; k < kGaussianTaps; ++k) {
    const int src = y + k - kGaussianRadius;
    rows[k] = src >= 0 && src < height ? image + src * row_size : zeros;
  }
}

void FilterWindowRows(const float* const rows[kGaussianTaps], size_t n, float* __restrict out) {
  const std::array<float, kGaussianTaps>& g = GaussianWindow();
  for (size_t i = 0; i < n; ++i) {
    float sum = 0.0f;
    for (int k = 0; k < kGaussianTaps; ++k) sum += g[k] * rows[k][i];
    out[i] = sum;
  }
}

}  // namespace m4d
