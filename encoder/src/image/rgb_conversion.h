// Conversion of gray and RGBA images to RGB, the form rendering and the losses work in.
#ifndef M4D_ENCODER_IMAGE_RGB_CONVERSION_H_
#define M4D_ENCODER_IMAGE_RGB_CONVERSION_H_

#include "encoder/src/image/image.h"
#include "sdk/src/common/status.h"

namespace m4d {

// Gray is replicated to three channels, RGB copied, and RGBA composited over `background`
// (alpha not premultiplied: rgb * a + background * (1 - a)), as 3DGS loads RGBA training
// views. *rgb may be `image`.
Status ConvertToRgb(const Image& image, const float background[3], Image* rgb);

}  // namespace m4d

#endif  // M4D_ENCODER_IMAGE_RGB_CONVERSION_H_
