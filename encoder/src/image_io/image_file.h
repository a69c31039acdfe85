// Reading an image file whose format is given by its content, for dataset loaders.
#ifndef M4D_ENCODER_IMAGE_IO_IMAGE_FILE_H_
#define M4D_ENCODER_IMAGE_IO_IMAGE_FILE_H_

#include <string>

#include "encoder/src/image/image.h"
#include "sdk/src/common/status.h"

namespace m4d {

// Reads a PNG or JPEG file (see png_io.h and jpeg_io.h), recognised by its signature, not by
// its name. Other content gives M4D_ERR_UNSUPPORTED.
Status ReadImageFile(const std::string& path, Image* image);

}  // namespace m4d

#endif  // M4D_ENCODER_IMAGE_IO_IMAGE_FILE_H_
