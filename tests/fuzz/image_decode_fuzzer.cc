// libFuzzer target for the image readers: the input is a PNG or JPEG file (or anything else).
// Decoding must fail cleanly or give an image of the promised shape, never crash or leak.
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "encoder/src/image_io/jpeg_io.h"
#include "encoder/src/image_io/png_io.h"

namespace {

void Decode(m4d::Status (*decode)(const uint8_t*, size_t, m4d::Image*), const uint8_t* data,
            size_t size) {
  m4d::Image image;
  if (!decode(data, size, &image).ok()) return;
  if (!m4d::CheckImage(image, "fuzz").ok()) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  Decode(m4d::DecodePng, data, size);
  Decode(m4d::DecodeJpeg, data, size);
  return 0;
}
