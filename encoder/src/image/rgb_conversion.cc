#include "encoder/src/image/rgb_conversion.h"

#include <cstddef>
#include <utility>

namespace m4d {

Status ConvertToRgb(const Image& image, const float background[3], Image* rgb) {
  M4D_RETURN_IF_ERROR(CheckImage(image, "rgb conversion"));
  Image out(image.width, image.height, 3);
  const size_t pixels = static_cast<size_t>(image.width) * image.height;
  const float* in = image.pixels.data();
  float* o = out.pixels.data();
  for (size_t p = 0; p < pixels; ++p, o += 3) {
    if (image.channels == 1) {
      o[0] = o[1] = o[2] = in[p];
    } else if (image.channels == 3) {
      for (int c = 0; c < 3; ++c) o[c] = in[3 * p + c];
    } else {
      const float alpha = in[4 * p + 3];
      for (int c = 0; c < 3; ++c) o[c] = in[4 * p + c] * alpha + background[c] * (1.0f - alpha);
    }
  }
  *rgb = std::move(out);
  return Status::Ok();
}

}  // namespace m4d
