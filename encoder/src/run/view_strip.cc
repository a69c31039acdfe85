#include "encoder/src/run/view_strip.h"

#include <algorithm>
#include <filesystem>

#include "encoder/src/image_io/png_io.h"

namespace m4d {

constexpr int kGap = 4;

Status ViewStrip(const std::vector<const Image*>& images, Image* strip) {
  if (images.empty()) return Status(M4D_ERR_INVALID_ARG, "view strip: no images");
  const int height = images[0]->height;
  int width = -kGap;
  for (const Image* image : images) {
    M4D_RETURN_IF_ERROR(CheckImage(*image, "view strip image"));
    if (image->height != height || image->channels != 3) {
      return Status(M4D_ERR_INVALID_ARG, "view strip: images differ in height or are not RGB");
    }
    width += image->width + kGap;
  }
  *strip = Image(width, height, 3, 1.0f);
  int x0 = 0;
  for (const Image* image : images) {
    for (int y = 0; y < height; ++y) {
      std::copy(image->row(y), image->row(y) + image->row_size(), strip->row(y) + 3 * x0);
    }
    x0 += image->width + kGap;
  }
  return Status::Ok();
}

Status WriteViewStrip(const std::string& path, const std::vector<const Image*>& images) {
  Image strip;
  M4D_RETURN_IF_ERROR(ViewStrip(images, &strip));
  const std::filesystem::path parent = std::filesystem::path(path).parent_path();
  std::error_code ec;
  if (!parent.empty()) std::filesystem::create_directories(parent, ec);
  return WritePng(path, strip);
}

}  // namespace m4d
