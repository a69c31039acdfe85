#include "encoder/src/capture/camera_downscale.h"

#include <string>

namespace m4d {

Status DownscaleCamera(int factor, Camera* camera) {
  const int width = factor > 0 ? camera->width / factor : 0;
  const int height = factor > 0 ? camera->height / factor : 0;
  if (width < 1 || height < 1) {
    return Status(M4D_ERR_INVALID_ARG,
                  "camera: downscale " + std::to_string(factor) + " leaves no pixels");
  }
  const double sx = static_cast<double>(width) / camera->width;
  const double sy = static_cast<double>(height) / camera->height;
  camera->fx = static_cast<float>(camera->fx * sx);
  camera->cx = static_cast<float>(camera->cx * sx);
  camera->fy = static_cast<float>(camera->fy * sy);
  camera->cy = static_cast<float>(camera->cy * sy);
  camera->width = width;
  camera->height = height;
  return Status::Ok();
}

}  // namespace m4d
