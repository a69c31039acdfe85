// Image resizing by area averaging, for dataset loaders that train at a lower resolution
// (e.g. N3DV at half resolution).
#ifndef M4D_ENCODER_IMAGE_AREA_RESIZE_H_
#define M4D_ENCODER_IMAGE_AREA_RESIZE_H_

#include "encoder/src/image/image.h"
#include "sdk/src/common/status.h"

namespace m4d {

// Each output pixel is the mean of the input over the rectangle it covers (input size /
// output size pixels along each axis), with partly covered input pixels weighted by the
// covered fraction. For an integer factor this is the box filter: the mean of each
// factor x factor block. Meant for downscaling (upscaling replicates pixels). *out may be
// `in`. M4D_ERR_LIMIT when the output, or the intermediate of in.height rows of
// `width` pixels, exceeds kMaxImageBytes.
Status ResizeArea(const Image& in, int width, int height, Image* out);

}  // namespace m4d

#endif  // M4D_ENCODER_IMAGE_AREA_RESIZE_H_
