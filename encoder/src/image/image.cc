#include "encoder/src/image/image.h"

namespace m4d {

void Reshape(int width, int height, int channels, Image* image) {
  image->width = width;
  image->height = height;
  image->channels = channels;
  image->pixels.resize(static_cast<size_t>(width) * height * channels);
}

Status CheckImageShape(int width, int height, int channels, const std::string& what) {
  if (width <= 0 || height <= 0) {
    return Status(M4D_ERR_INVALID_ARG, what + ": empty image (" + std::to_string(width) + " x " +
                                           std::to_string(height) + ")");
  }
  if (channels != 1 && channels != 3 && channels != 4) {
    return Status(M4D_ERR_INVALID_ARG,
                  what + ": " + std::to_string(channels) + " channels, expected 1, 3 or 4");
  }
  const size_t max_pixels = kMaxImageBytes / sizeof(float) / static_cast<size_t>(channels);
  if (static_cast<size_t>(width) > max_pixels / static_cast<size_t>(height)) {
    return LimitError(what + ": " + std::to_string(width) + " x " + std::to_string(height) + " x " +
                      std::to_string(channels) + " exceeds the limit of " +
                      std::to_string(kMaxImageBytes) + " bytes of float samples");
  }
  return Status::Ok();
}

Status CheckImage(const Image& image, const std::string& what) {
  M4D_RETURN_IF_ERROR(CheckImageShape(image.width, image.height, image.channels, what));
  if (image.pixels.size() != image.row_size() * image.height) {
    return Status(M4D_ERR_INVALID_ARG, what + ": pixel count does not match the shape");
  }
  return Status::Ok();
}

Status CheckSameShape(const Image& a, const Image& b, const std::string& what) {
  M4D_RETURN_IF_ERROR(CheckImage(a, what));
  M4D_RETURN_IF_ERROR(CheckImage(b, what));
  if (a.width != b.width || a.height != b.height || a.channels != b.channels) {
    return Status(M4D_ERR_INVALID_ARG,
                  what + ": shapes differ (" + std::to_string(a.width) + "x" +
                      std::to_string(a.height) + "x" + std::to_string(a.channels) + " vs " +
                      std::to_string(b.width) + "x" + std::to_string(b.height) + "x" +
                      std::to_string(b.channels) + ")");
  }
  return Status::Ok();
}

}  // namespace m4d
