#include "encoder/src/metrics/photometric_loss.h"

#include <cstddef>

#include "encoder/src/metrics/l1_loss.h"
#include "encoder/src/metrics/ssim.h"

namespace m4d {

Status PhotometricLoss::Evaluate(const Image& rendered, const Image& target,
                                 PhotometricLossValue* value, Image* grad) {
  M4D_RETURN_IF_ERROR(L1Loss(rendered, target, &value->l1));
  M4D_RETURN_IF_ERROR(SsimZeroPadded(rendered, target, &value->ssim, grad, &ssim_workspace_));
  value->loss = (1.0 - ssim_weight_) * value->l1 + ssim_weight_ * (1.0 - value->ssim);
  if (!grad) return Status::Ok();
  // grad holds dSSIM/drendered. dL = (1 - lambda) dL1 - lambda dSSIM with dL1 the sign of
  // the difference over N (l1_loss.h), added here in one pass.
  const size_t n = grad->pixels.size();
  const float l1_step = static_cast<float>((1.0 - ssim_weight_) / static_cast<double>(n));
  const float ssim_weight = static_cast<float>(ssim_weight_);
  const float* r = rendered.pixels.data();
  const float* t = target.pixels.data();
  float* g = grad->pixels.data();
  for (size_t i = 0; i < n; ++i) {
    const float l1 = r[i] > t[i] ? l1_step : (r[i] < t[i] ? -l1_step : 0.0f);
    g[i] = l1 - ssim_weight * g[i];
  }
  return Status::Ok();
}

}  // namespace m4d
