// PNG reading and writing through libpng.
//
// Reading accepts every PNG colour type at every bit depth. The result has 1 channel for
// gray, 3 for RGB and palette images, and 4 (RGBA) whenever the file has alpha: an alpha
// channel, a tRNS transparency entry, or gray + alpha (expanded to RGBA). Samples map to
// [0, 1] as v / 255 or v / 65535, with no gamma or colour-profile conversion.
//
// Errors: M4D_ERR_INVALID_ARG for a file that cannot be opened, M4D_ERR_UNSUPPORTED for data
// without the PNG signature, M4D_ERR_BITSTREAM for corrupt or truncated data, M4D_ERR_LIMIT for
// images beyond kMaxImageBytes (rejected from the header, before decoding) and for files
// larger than kMaxImageBytes.
#ifndef M4D_ENCODER_IMAGE_IO_PNG_IO_H_
#define M4D_ENCODER_IMAGE_IO_PNG_IO_H_

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "encoder/src/image/image.h"
#include "sdk/src/common/status.h"

namespace m4d {

Status ReadPng(const std::string& path, Image* image);
Status DecodePng(const uint8_t* data, size_t size, Image* image);

// Writes an 8-bit gray, RGB or RGBA PNG (1, 3 or 4 channels) with samples FloatToByte(v).
Status WritePng(const std::string& path, const Image& image);
Status EncodePng(const Image& image, std::vector<uint8_t>* bytes);

}  // namespace m4d

#endif  // M4D_ENCODER_IMAGE_IO_PNG_IO_H_
