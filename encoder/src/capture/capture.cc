#include "encoder/src/capture/capture.h"

#include <algorithm>

namespace m4d {

std::vector<int> Capture::TrainCameras() const {
  std::vector<int> train;
  for (int c = 0; c < camera_count(); ++c) {
    if (!IsTestCamera(c)) train.push_back(c);
  }
  return train;
}

bool Capture::IsTestCamera(int index) const {
  return std::find(test_cameras.begin(), test_cameras.end(), index) != test_cameras.end();
}

Status Capture::LoadImage(int frame, int camera, Image* rgb) const {
  if (frame < 0 || frame >= frame_count || camera < 0 || camera >= camera_count()) {
    return Status(M4D_ERR_INVALID_ARG, "capture: view (frame " + std::to_string(frame) +
                                           ", camera " + std::to_string(camera) + ") out of range");
  }
  if (!frames) return Status(M4D_ERR_INVALID_ARG, "capture: no frame source");
  return frames->Load(frame, camera, rgb);
}

}  // namespace m4d
