// The photometric loss of a render restricted to its focus tiles (encoder/src/raster/tile_focus.h),
// each pixel weighted as in the loss of the whole image (photometric_loss.h), the gradient zero
// outside the pixels it is taken over. The trained splats' pixels get the whole image's
// gradient when the SSIM term's reach around them, 10 pixels (two 11x11 windows), holds what
// the whole render holds there. Either
// - the focus was grown by a tile around the trained splats: the loss is taken over its
//   bounding rectangle, the tiles there that were not rendered taken as the target (no loss);
// - or the caller gives `unfocused`, what the render holds outside the focus (the frozen
//   layers' render alone, encoder/src/train/frozen_layer_views.h): the loss is taken over the
//   rectangle grown by a tile, the tiles not rendered read from `unfocused`. The focus then needs
//   no margin, and a quarter to a half fewer tiles are rendered.
// The loss value is the mean over those pixels.
#ifndef M4D_ENCODER_METRICS_FOCUSED_LOSS_H_
#define M4D_ENCODER_METRICS_FOCUSED_LOSS_H_

#include "encoder/src/image/image.h"
#include "encoder/src/metrics/photometric_loss.h"
#include "encoder/src/raster/tile_focus.h"
#include "sdk/src/common/status.h"

namespace m4d {

class FocusedLoss {
 public:
  explicit FocusedLoss(double ssim_weight = kDefaultSsimWeight) : loss_(ssim_weight) {}

  // The loss of `rendered` against `target` (same shape, 3 channels) around the focus
  // tiles; *grad is dL/drendered in rendered's shape. `unfocused` (null: see above) has their
  // shape too.
  Status Evaluate(const Image& rendered, const Image& target, const TileFocus& focus,
                  const Image* unfocused, PhotometricLossValue* value, Image* grad);

 private:
  PhotometricLoss loss_;
  Image rendered_crop_, target_crop_, grad_crop_;
};

}  // namespace m4d

#endif  // M4D_ENCODER_METRICS_FOCUSED_LOSS_H_
