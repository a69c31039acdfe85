// The L1 term of the training loss.
#ifndef M4D_ENCODER_METRICS_L1_LOSS_H_
#define M4D_ENCODER_METRICS_L1_LOSS_H_

#include "encoder/src/image/image.h"
#include "sdk/src/common/status.h"

namespace m4d {

// Mean absolute difference over all samples of two images of the same shape. With grad
// non-null, also dL1/drendered = sign(rendered - target) / N (0 where they are equal), HWC in
// rendered's shape, into *grad (its storage is reused).
Status L1Loss(const Image& rendered, const Image& target, double* loss, Image* grad = nullptr);

}  // namespace m4d

#endif  // M4D_ENCODER_METRICS_L1_LOSS_H_
