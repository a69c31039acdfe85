// Image: the float image that rendering, datasets and the training losses share. Pixels are
// interleaved row-major (HWC) with row 0 at the top; values are nominally in [0, 1] and are
// used as stored (no gamma conversion, as in 3DGS training).
#ifndef M4D_ENCODER_IMAGE_IMAGE_H_
#define M4D_ENCODER_IMAGE_IMAGE_H_

#include <cstddef>
#include <string>
#include <vector>

#include "sdk/src/common/status.h"

namespace m4d {

// Largest decoded image, in bytes of float samples (width * height * channels * 4): 2^28,
// e.g. 4096 x 4096 RGBA or 4K RGB. Readers reject larger files before allocating.
constexpr size_t kMaxImageBytes = size_t{1} << 28;

struct Image {
  Image() = default;
  Image(int w, int h, int c, float value = 0.0f)
      : width(w), height(h), channels(c), pixels(static_cast<size_t>(w) * h * c, value) {}

  size_t row_size() const { return static_cast<size_t>(width) * channels; }
  float* row(int y) { return pixels.data() + y * row_size(); }
  const float* row(int y) const { return pixels.data() + y * row_size(); }
  float& at(int x, int y, int c) { return row(y)[static_cast<size_t>(x) * channels + c]; }
  float at(int x, int y, int c) const { return row(y)[static_cast<size_t>(x) * channels + c]; }

  int width = 0;
  int height = 0;
  int channels = 0;           // 1 (gray), 3 (RGB) or 4 (RGBA, alpha not premultiplied)
  std::vector<float> pixels;  // height * width * channels
};

// Gives *image this shape, reusing its storage (for outputs such as gradients that are
// written every call); the sample values are unspecified afterwards.
void Reshape(int width, int height, int channels, Image* image);

// OK when width and height are positive, channels is 1, 3 or 4 and the samples fit
// kMaxImageBytes; otherwise M4D_ERR_LIMIT (size) or M4D_ERR_INVALID_ARG, naming `what`.
Status CheckImageShape(int width, int height, int channels, const std::string& what);

// CheckImageShape, plus pixels.size() matching the shape.
Status CheckImage(const Image& image, const std::string& what);

// OK when both images are valid and have the same width, height and channels.
Status CheckSameShape(const Image& a, const Image& b, const std::string& what);

}  // namespace m4d

#endif  // M4D_ENCODER_IMAGE_IMAGE_H_
