#include "encoder/src/dataset/image_file_source.h"

#include "encoder/src/image/rgb_conversion.h"
#include "encoder/src/image_io/image_file.h"

namespace m4d {

Status ReadViewImage(const std::string& path, int width, int height, Image* rgb) {
  M4D_RETURN_IF_ERROR(ReadImageFile(path, rgb));
  if (rgb->width != width || rgb->height != height) {
    return Status(M4D_ERR_INVALID_ARG, "'" + path + "' is " + std::to_string(rgb->width) + "x" +
                                           std::to_string(rgb->height) + ", expected " +
                                           std::to_string(width) + "x" + std::to_string(height));
  }
  const float black[3] = {0, 0, 0};
  return ConvertToRgb(*rgb, black, rgb);
}

ImageFileSource::ImageFileSource(std::vector<std::vector<std::string>> paths,
                                 const std::vector<std::vector<Camera>>& cameras) {
  views_.resize(paths.size());
  for (size_t f = 0; f < paths.size(); ++f) {
    for (size_t c = 0; c < paths[f].size(); ++c) {
      views_[f].push_back({std::move(paths[f][c]), cameras[f][c].width, cameras[f][c].height});
    }
  }
}

Status ImageFileSource::Load(int frame, int camera, Image* rgb) {
  const View& view = views_[frame][camera];
  return ReadViewImage(view.path, view.width, view.height, rgb);
}

}  // namespace m4d
