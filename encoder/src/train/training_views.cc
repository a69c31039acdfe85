#include "encoder/src/train/training_views.h"

#include <string>
#include <utility>

namespace m4d {

Status LoadTrainingViews(const Capture& capture, int frame, const std::vector<int>& cameras,
                         TrainingViews* views) {
  TrainingViews loaded;
  for (int c : cameras) {
    Image image;
    M4D_RETURN_IF_ERROR(capture.LoadImage(frame, c, &image));
    loaded.camera_indices.push_back(c);
    loaded.cameras.push_back(capture.camera(frame, c));
    loaded.images.push_back(std::move(image));
  }
  M4D_RETURN_IF_ERROR(CheckTrainingViews(loaded));
  *views = std::move(loaded);
  return Status::Ok();
}

Status CheckTrainingViews(const TrainingViews& views) {
  if (views.images.size() != views.cameras.size()) {
    return Status(M4D_ERR_INVALID_ARG, "training views: cameras and images differ in number");
  }
  for (size_t v = 0; v < views.cameras.size(); ++v) {
    const std::string what = "training view " + std::to_string(v);
    M4D_RETURN_IF_ERROR(ValidateCamera(views.cameras[v]));
    const Image& image = views.images[v];
    M4D_RETURN_IF_ERROR(CheckImage(image, what));
    if (image.channels != 3 || image.width != views.cameras[v].width ||
        image.height != views.cameras[v].height) {
      return Status(M4D_ERR_INVALID_ARG, what + ": image is not RGB at the camera's size");
    }
  }
  return Status::Ok();
}

}  // namespace m4d
