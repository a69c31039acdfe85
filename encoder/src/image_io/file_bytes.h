// Whole-file reads and writes for the image codecs, which decode from and encode to memory.
#ifndef M4D_ENCODER_IMAGE_IO_FILE_BYTES_H_
#define M4D_ENCODER_IMAGE_IO_FILE_BYTES_H_

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "encoder/src/image/image.h"
#include "sdk/src/common/status.h"

namespace m4d {

// Reads the whole file into *bytes. M4D_ERR_INVALID_ARG when it cannot be opened or read,
// M4D_ERR_LIMIT when it holds more than max_bytes (checked while reading, so a huge or
// endless file never allocates more than max_bytes).
Status ReadFileBytes(const std::string& path, size_t max_bytes, std::vector<uint8_t>* bytes);

// Reads a file (at most kMaxImageBytes) and decodes its bytes with `decode`; a failure's
// message ends with the path.
using ImageDecoder = Status (*)(const uint8_t* data, size_t size, Image* image);
Status DecodeImageFile(const std::string& path, ImageDecoder decode, Image* image);

// Creates or replaces the file, atomically (io/atomic_file.h). M4D_ERR_INVALID_ARG when it
// cannot be written.
Status WriteFileBytes(const std::string& path, const std::vector<uint8_t>& bytes);

}  // namespace m4d

#endif  // M4D_ENCODER_IMAGE_IO_FILE_BYTES_H_
