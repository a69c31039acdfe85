#include "encoder/src/image_io/image_file.h"

#include <algorithm>
#include <cstdint>
#include <initializer_list>

#include "encoder/src/image_io/file_bytes.h"
#include "encoder/src/image_io/jpeg_io.h"
#include "encoder/src/image_io/png_io.h"

namespace m4d {
namespace {

bool StartsWith(const uint8_t* data, size_t size, std::initializer_list<uint8_t> prefix) {
  return size >= prefix.size() && std::equal(prefix.begin(), prefix.end(), data);
}

Status DecodeAny(const uint8_t* data, size_t size, Image* image) {
  if (StartsWith(data, size, {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'})) {
    return DecodePng(data, size, image);
  }
  if (StartsWith(data, size, {0xff, 0xd8, 0xff})) return DecodeJpeg(data, size, image);
  return Status(M4D_ERR_UNSUPPORTED, "image: neither PNG nor JPEG");
}

}  // namespace

Status ReadImageFile(const std::string& path, Image* image) {
  return DecodeImageFile(path, DecodeAny, image);
}

}  // namespace m4d
