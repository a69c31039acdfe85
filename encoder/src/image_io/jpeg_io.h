// JPEG reading and writing through libjpeg.
//
// Reading gives 1 channel for grayscale files and 3 (RGB) for YCbCr or RGB files, samples
// v / 255; EXIF orientation and colour profiles are not applied. CMYK and YCCK files give
// M4D_ERR_UNSUPPORTED. libjpeg's corrupt-data warnings (a truncated file, a bad Huffman code)
// are errors here: libjpeg would fill the missing part with gray and carry on.
//
// Errors: M4D_ERR_INVALID_ARG for a file that cannot be opened, M4D_ERR_BITSTREAM for corrupt,
// truncated or non-JPEG data, M4D_ERR_LIMIT for images beyond kMaxImageBytes (rejected from
// the header, before decoding) and for files larger than kMaxImageBytes.
#ifndef M4D_ENCODER_IMAGE_IO_JPEG_IO_H_
#define M4D_ENCODER_IMAGE_IO_JPEG_IO_H_

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "encoder/src/image/image.h"
#include "sdk/src/common/status.h"

namespace m4d {

Status ReadJpeg(const std::string& path, Image* image);
Status DecodeJpeg(const uint8_t* data, size_t size, Image* image);

// Writes a baseline JPEG of a gray or RGB image with samples FloatToByte(v), quality 1..100
// (libjpeg's scale) and no chroma subsampling (4:4:4). RGBA, a quality outside 1..100 or a
// side above 65500 pixels (the format's limit) give M4D_ERR_INVALID_ARG.
Status WriteJpeg(const std::string& path, const Image& image, int quality);
Status EncodeJpeg(const Image& image, int quality, std::vector<uint8_t>* bytes);

}  // namespace m4d

#endif  // M4D_ENCODER_IMAGE_IO_JPEG_IO_H_
