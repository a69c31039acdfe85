// Peak signal-to-noise ratio for images with values in [0, 1] (peak 1):
// PSNR = 10 log10(1 / MSE) dB, MSE the mean squared difference over all samples of all
// channels, accumulated in double. Equal images (MSE 0) give +infinity.
#ifndef M4D_ENCODER_METRICS_PSNR_H_
#define M4D_ENCODER_METRICS_PSNR_H_

#include "encoder/src/image/image.h"
#include "sdk/src/common/status.h"

namespace m4d {

Status MeanSquaredError(const Image& a, const Image& b, double* mse);

Status Psnr(const Image& a, const Image& b, double* psnr_db);

// PSNR over the pixels a one-channel mask of the same width and height selects, weighted by
// the mask: MSE = sum_p m(p) sum_c (a - b)^2 / (channels * sum_p m(p)). Masks are 0/1 or
// weights in [0, 1]; negative or non-finite weights, or a zero total weight, give
// M4D_ERR_INVALID_ARG.
Status PsnrMasked(const Image& a, const Image& b, const Image& mask, double* psnr_db);

}  // namespace m4d

#endif  // M4D_ENCODER_METRICS_PSNR_H_
