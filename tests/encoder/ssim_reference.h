// A direct, double-precision SSIM for checking the fast one: every map value sums its 11 x 11
// window with explicit loops, exactly as the definition reads (ssim.h), and derivatives are
// central finite differences of it.
#ifndef M4D_TESTS_ENCODER_SSIM_REFERENCE_H_
#define M4D_TESTS_ENCODER_SSIM_REFERENCE_H_

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "encoder/src/image/image.h"

namespace m4d {
namespace testing {

struct DoubleImage {
  explicit DoubleImage(const Image& image)
      : width(image.width),
        height(image.height),
        channels(image.channels),
        v(image.pixels.begin(), image.pixels.end()) {}

  // Zero outside the image: the padding of the zero-padded convention.
  double at(int x, int y, int c) const {
    if (x < 0 || y < 0 || x >= width || y >= height) return 0.0;
    return v[(static_cast<size_t>(y) * width + x) * channels + c];
  }
  double& at(int x, int y, int c) { return v[(static_cast<size_t>(y) * width + x) * channels + c]; }

  int width, height, channels;
  std::vector<double> v;
};

// The 2-D window: the outer product of the normalised 1-D Gaussian, sigma 1.5.
inline double Window(int dx, int dy) {
  static const std::vector<double> g = [] {
    std::vector<double> w(11);
    double sum = 0;
    for (int k = -5; k <= 5; ++k) sum += w[k + 5] = std::exp(-k * k / (2 * 1.5 * 1.5));
    for (double& v : w) v /= sum;
    return w;
  }();
  return g[dx + 5] * g[dy + 5];
}

// The SSIM map at pixel (px, py), channel c.
inline double SsimAt(const DoubleImage& x, const DoubleImage& y, int px, int py, int c) {
  double mx = 0, my = 0, exx = 0, eyy = 0, exy = 0;
  for (int dy = -5; dy <= 5; ++dy) {
    for (int dx = -5; dx <= 5; ++dx) {
      const double w = Window(dx, dy);
      const double a = x.at(px + dx, py + dy, c), b = y.at(px + dx, py + dy, c);
      mx += w * a;
      my += w * b;
      exx += w * a * a;
      eyy += w * b * b;
      exy += w * a * b;
    }
  }
  const double c1 = 0.01 * 0.01, c2 = 0.03 * 0.03;
  const double sxx = exx - mx * mx, syy = eyy - my * my, sxy = exy - mx * my;
  return (2 * mx * my + c1) * (2 * sxy + c2) / ((mx * mx + my * my + c1) * (sxx + syy + c2));
}

// Mean of the map over every pixel (zero-padded) or over the pixels whose window lies in the
// image (valid).
inline double ReferenceSsim(const DoubleImage& x, const DoubleImage& y, bool valid) {
  const int m = valid ? 5 : 0;
  double sum = 0;
  int count = 0;
  for (int c = 0; c < x.channels; ++c) {
    for (int py = m; py < x.height - m; ++py) {
      for (int px = m; px < x.width - m; ++px, ++count) sum += SsimAt(x, y, px, py, c);
    }
  }
  return sum / count;
}

// Central difference of the zero-padded mean SSIM with respect to x(qx, qy, c), step h.
// Only map values within 5 pixels of q depend on x(q), so only those are summed.
inline double SsimDerivative(DoubleImage x, const DoubleImage& y, int qx, int qy, int c, double h) {
  auto local_sum = [&] {
    double sum = 0;
    for (int py = std::max(0, qy - 5); py <= std::min(x.height - 1, qy + 5); ++py) {
      for (int px = std::max(0, qx - 5); px <= std::min(x.width - 1, qx + 5); ++px) {
        sum += SsimAt(x, y, px, py, c);
      }
    }
    return sum;
  };
  const double x0 = x.at(qx, qy, c);
  x.at(qx, qy, c) = x0 + h;
  const double plus = local_sum();
  x.at(qx, qy, c) = x0 - h;
  const double minus = local_sum();
  return (plus - minus) / (2 * h) / static_cast<double>(x.v.size());
}

// Uniform noise in [0, 1].
inline Image RandomImage(int width, int height, int channels, std::mt19937* rng) {
  Image image(width, height, channels);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  for (float& v : image.pixels) v = unit(*rng);
  return image;
}

// 0.7 x + 0.3 noise: similar to x but not equal (SSIM about 0.9 against uniform noise x).
inline Image CorrelatedImage(const Image& x, std::mt19937* rng) {
  Image y = RandomImage(x.width, x.height, x.channels, rng);
  for (size_t i = 0; i < y.pixels.size(); ++i)
    y.pixels[i] = 0.7f * x.pixels[i] + 0.3f * y.pixels[i];
  return y;
}

}  // namespace testing
}  // namespace m4d

#endif  // M4D_TESTS_ENCODER_SSIM_REFERENCE_H_
