#include "encoder/src/metrics/psnr.h"

#include <cmath>
#include <cstddef>
#include <limits>

namespace m4d {
namespace {

double PsnrFromMse(double mse) {
  if (mse == 0) return std::numeric_limits<double>::infinity();
  return -10.0 * std::log10(mse);
}

}  // namespace

Status MeanSquaredError(const Image& a, const Image& b, double* mse) {
  M4D_RETURN_IF_ERROR(CheckSameShape(a, b, "mse"));
  double sum = 0;
  for (size_t i = 0; i < a.pixels.size(); ++i) {
    const double d = static_cast<double>(a.pixels[i]) - b.pixels[i];
    sum += d * d;
  }
  *mse = sum / static_cast<double>(a.pixels.size());
  return Status::Ok();
}

Status Psnr(const Image& a, const Image& b, double* psnr_db) {
  double mse = 0;
  M4D_RETURN_IF_ERROR(MeanSquaredError(a, b, &mse));
  *psnr_db = PsnrFromMse(mse);
  return Status::Ok();
}

Status PsnrMasked(const Image& a, const Image& b, const Image& mask, double* psnr_db) {
  M4D_RETURN_IF_ERROR(CheckSameShape(a, b, "masked psnr"));
  M4D_RETURN_IF_ERROR(CheckImage(mask, "masked psnr mask"));
  if (mask.channels != 1 || mask.width != a.width || mask.height != a.height) {
    return Status(M4D_ERR_INVALID_ARG, "masked psnr: the mask must be one channel, image-sized");
  }
  double weighted = 0, weight = 0;
  const size_t pixels = mask.pixels.size();
  for (size_t p = 0; p < pixels; ++p) {
    const double m = mask.pixels[p];
    if (!(m >= 0) || !std::isfinite(m)) {
      return Status(M4D_ERR_INVALID_ARG, "masked psnr: mask weights must be finite and >= 0");
    }
    if (m == 0) continue;
    double sum = 0;
    for (int c = 0; c < a.channels; ++c) {
      const size_t i = p * a.channels + c;
      const double d = static_cast<double>(a.pixels[i]) - b.pixels[i];
      sum += d * d;
    }
    weighted += m * sum;
    weight += m;
  }
  if (weight == 0) return Status(M4D_ERR_INVALID_ARG, "masked psnr: the mask selects nothing");
  *psnr_db = PsnrFromMse(weighted / (weight * a.channels));
  return Status::Ok();
}

}  // namespace m4d
