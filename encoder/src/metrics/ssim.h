// SSIM (Wang et al. 2004) of images with values in [0, 1], per channel. The local statistics
// are weighted by the 11 x 11 Gaussian window G (sigma 1.5):
//   mu_x = G*x,  sigma_x^2 = G*(x^2) - mu_x^2,  sigma_xy = G*(x y) - mu_x mu_y,
//   SSIM = (2 mu_x mu_y + C1) (2 sigma_xy + C2) / ((mu_x^2 + mu_y^2 + C1) (sigma_x^2 +
//          sigma_y^2 + C2)),  C1 = 0.01^2, C2 = 0.03^2,
// and the result is the mean of this map over its pixels and all channels. Two conventions:
//
//  - SsimZeroPadded: the reference 3DGS implementation's, in its training loss and in its
//    evaluation script. G is a 'same'-size 2-D convolution with zero padding and no
//    renormalisation at the borders, so the map covers every pixel and the 5-pixel border
//    sees statistics of a darkened neighbourhood. Use for training, and for numbers
//    comparable to those 3DGS-derived papers report.
//  - SsimValid: Wang et al.'s reference ('valid' filtering, no padding): the map covers only
//    the pixels whose whole window lies in the image, (width - 10) x (height - 10). Use for
//    evaluation reports in the standard convention. (Later reference scripts also downscale
//    large images first; this does not.)
//
// Both compute in float with per-row sums in double, split rows across threads, and give
// results that do not depend on the thread count.
#ifndef M4D_ENCODER_METRICS_SSIM_H_
#define M4D_ENCODER_METRICS_SSIM_H_

#include <vector>

#include "encoder/src/image/image.h"
#include "sdk/src/common/status.h"

namespace m4d {

constexpr float kSsimC1 = 0.01f * 0.01f;
constexpr float kSsimC2 = 0.03f * 0.03f;

// Scratch buffers (3 floats per sample with the gradient), kept by callers that evaluate SSIM
// every training iteration so that they are allocated once. Contents are internal.
struct SsimWorkspace {
  std::vector<float> partials;
  std::vector<double> row_sums;
};

// Mean SSIM of x and y (same shape) in the zero-padded convention. With grad_x non-null,
// also d(mean SSIM)/dx, HWC in x's shape, into *grad_x (its storage is reused).
Status SsimZeroPadded(const Image& x, const Image& y, double* ssim, Image* grad_x = nullptr,
                      SsimWorkspace* workspace = nullptr);

// Mean SSIM of x and y (same shape, at least 11 x 11) in the 'valid' convention.
Status SsimValid(const Image& x, const Image& y, double* ssim, SsimWorkspace* workspace = nullptr);

}  // namespace m4d

#endif  // M4D_ENCODER_METRICS_SSIM_H_
