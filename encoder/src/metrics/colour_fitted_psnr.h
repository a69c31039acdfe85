// PSNR after the render's colour is fitted to the image, per channel, by the gain and offset
// that minimise the squared error (least squares; the result clamped to [0, 1]). The cameras
// of a rig differ in exposure and white balance; a model renders in the training cameras'
// common colour (train/camera_colour.h), which a held-out camera does not share. The gap
// between this PSNR and the plain one is the part of a held-out view's error that is the
// camera's colour rather than the scene's content. Reported beside the plain PSNR, never
// instead of it.
#ifndef M4D_ENCODER_METRICS_COLOUR_FITTED_PSNR_H_
#define M4D_ENCODER_METRICS_COLOUR_FITTED_PSNR_H_

#include "encoder/src/image/image.h"
#include "sdk/src/common/status.h"

namespace m4d {

// `rendered` and `truth` of the same shape. A constant channel of `rendered` gets gain 0 and
// the truth's mean as offset.
Status ColourFittedPsnr(const Image& rendered, const Image& truth, double* psnr_db);

}  // namespace m4d

#endif  // M4D_ENCODER_METRICS_COLOUR_FITTED_PSNR_H_
