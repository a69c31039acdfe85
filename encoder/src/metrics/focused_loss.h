// The photometric loss of a render restricted to its focus tiles (render/tile_focus.h): the
// loss over the focus's bounding rectangle, each pixel weighted as in the loss of the whole
// image (photometric_loss.h), the tiles there that were not rendered taken as the target
// (no loss), and the gradient zero outside the rectangle.
//
// Where the focus is grown by a tile around the trained splats, their pixels' gradient is the
// whole image's: the SSIM term at a pixel reads the image within 10 pixels (two 11x11
// windows), less than the 16-pixel margin. The loss value is the rectangle's own mean.
#ifndef M4D_ENCODER_METRICS_FOCUSED_LOSS_H_
#define M4D_ENCODER_METRICS_FOCUSED_LOSS_H_

#include "common/status.h"
#include "image/image.h"
#include "metrics/photometric_loss.h"
#include "render/tile_focus.h"

namespace m4d {

class FocusedLoss {
 public:
  explicit FocusedLoss(double ssim_weight = kDefaultSsimWeight) : loss_(ssim_weight) {}

  // The loss of `rendered` against `target` (same shape, 3 channels) over the pixels of the
  // focus tiles; *grad is dL/drendered in rendered's shape (zero outside the focus).
  Status Evaluate(const Image& rendered, const Image& target, const TileFocus& focus,
                  PhotometricLossValue* value, Image* grad);

 private:
  PhotometricLoss loss_;
  Image rendered_crop_, target_crop_, grad_crop_;
};

}  // namespace m4d

#endif  // M4D_ENCODER_METRICS_FOCUSED_LOSS_H_
