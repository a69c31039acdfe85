#include "encoder/src/metrics/colour_fitted_psnr.h"

#include <algorithm>
#include <cstddef>

#include "encoder/src/metrics/psnr.h"

namespace m4d {
namespace {

// Least-squares gain and offset taking channel `c` of `x` to that of `y`.
void FitChannel(const Image& x, const Image& y, int c, double* gain, double* offset) {
  const size_t n = x.pixels.size() / static_cast<size_t>(x.channels);
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (size_t p = 0; p < n; ++p) {
    const double a = x.pixels[p * x.channels + c], b = y.pixels[p * y.channels + c];
    sx += a;
    sy += b;
    sxx += a * a;
    sxy += a * b;
  }
  const double mx = sx / n, my = sy / n;
  const double variance = sxx / n - mx * mx;
  *gain = variance > 1e-12 ? (sxy / n - mx * my) / variance : 0.0;
  *offset = my - *gain * mx;
}

}  // namespace

Status ColourFittedPsnr(const Image& rendered, const Image& truth, double* psnr_db) {
  M4D_RETURN_IF_ERROR(CheckSameShape(rendered, truth, "colour-fitted psnr"));
  Image fitted = rendered;
  for (int c = 0; c < rendered.channels; ++c) {
    double gain = 0, offset = 0;
    FitChannel(rendered, truth, c, &gain, &offset);
    for (size_t i = static_cast<size_t>(c); i < fitted.pixels.size(); i += rendered.channels) {
      const double v = gain * rendered.pixels[i] + offset;
      fitted.pixels[i] = static_cast<float>(std::clamp(v, 0.0, 1.0));
    }
  }
  return Psnr(fitted, truth, psnr_db);
}

}  // namespace m4d
