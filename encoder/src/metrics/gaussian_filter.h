// The separable 11-tap Gaussian window of SSIM (sigma 1.5) applied to interleaved (HWC) float
// images with zero padding: samples outside the image count as 0 and the window is not
// renormalised near the borders, as a zero-padded 2-D convolution computes it. The window is
// symmetric, so this filter is also its own adjoint (what back-propagation needs).
#ifndef M4D_ENCODER_METRICS_GAUSSIAN_FILTER_H_
#define M4D_ENCODER_METRICS_GAUSSIAN_FILTER_H_

#include <array>
#include <cstddef>

namespace m4d {

constexpr int kGaussianRadius = 5;
constexpr int kGaussianTaps = 2 * kGaussianRadius + 1;
constexpr double kGaussianSigma = 1.5;

// g[k] = exp(-(k - 5)^2 / (2 sigma^2)) / sum_j exp(-(j - 5)^2 / (2 sigma^2)).
const std::array<float, kGaussianTaps>& GaussianWindow();

// Horizontal pass over one row of `width` pixels of `channels` samples:
// out[x][c] = sum_k g[k] row[x + k - 5][c]. `padded` holds the row with 5 zero pixels on
// each side ((width + 10) * channels samples), so that callers can fill it from a vertical
// pass or form products while copying, and the loop needs no border cases.
void FilterPaddedRow(const float* padded, int width, int channels, float* out);

// The rows y - 5 .. y + 5 of an image of `height` rows of `row_size` samples, with `zeros`
// (row_size zero samples) standing in for rows outside the image.
void GatherWindowRows(const float* image, size_t row_size, int height, int y, const float* zeros,
                      const float* rows[kGaussianTaps]);

// Vertical pass over gathered rows: out[i] = sum_k g[k] rows[k][i] for i < n.
void FilterWindowRows(const float* const rows[kGaussianTaps], size_t n, float* out);

}  // namespace m4d

#endif  // M4D_ENCODER_METRICS_GAUSSIAN_FILTER_H_
