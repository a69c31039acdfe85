// The 3DGS training loss (Kerbl et al. 2023), which 4D-MoDe trains with:
//   L = (1 - lambda) L1 + lambda (1 - SSIM),  lambda = 0.2,
// with L1 the mean absolute error and SSIM the zero-padded convention (ssim.h), both over
// all pixels and channels of the rendered image against the target.
#ifndef M4D_ENCODER_METRICS_PHOTOMETRIC_LOSS_H_
#define M4D_ENCODER_METRICS_PHOTOMETRIC_LOSS_H_

#include "encoder/src/image/image.h"
#include "encoder/src/metrics/ssim.h"
#include "sdk/src/common/status.h"

namespace m4d {

constexpr double kDefaultSsimWeight = 0.2;  // lambda, the papers' value

struct PhotometricLossValue {
  double loss = 0;  // L
  double l1 = 0;    // the L1 term
  double ssim = 0;  // SSIM (the loss uses 1 - SSIM)
};

// Keeps its scratch buffers between calls: use one object per training thread.
class PhotometricLoss {
 public:
  explicit PhotometricLoss(double ssim_weight = kDefaultSsimWeight) : ssim_weight_(ssim_weight) {}

  // The loss of `rendered` against `target` (same shape). With grad non-null, also
  // dL/drendered, HWC in rendered's shape, into *grad (its storage is reused; not one of the
  // inputs).
  Status Evaluate(const Image& rendered, const Image& target, PhotometricLossValue* value,
                  Image* grad = nullptr);

  double ssim_weight() const { return ssim_weight_; }

 private:
  double ssim_weight_;
  SsimWorkspace ssim_workspace_;
};

}  // namespace m4d

#endif  // M4D_ENCODER_METRICS_PHOTOMETRIC_LOSS_H_
