// TrainingViews: the cameras and decoded images of one frame that a training stage fits,
// kept in memory (decoding every iteration would cost more than rendering small views).
#ifndef M4D_ENCODER_TRAIN_TRAINING_VIEWS_H_
#define M4D_ENCODER_TRAIN_TRAINING_VIEWS_H_

#include <vector>

#include "encoder/src/capture/capture.h"
#include "encoder/src/image/image.h"
#include "sdk/src/common/status.h"
#include "sdk/src/render/camera.h"

namespace m4d {

struct TrainingViews {
  std::vector<int> camera_indices;  // the capture's camera index of each view
  std::vector<Camera> cameras;
  std::vector<Image> images;  // RGB, the camera's size

  int size() const { return static_cast<int>(cameras.size()); }
};

// Loads the given cameras of `frame`. Fails on a bad index, a load error, or an image that
// is not RGB at its camera's size (M4D_ERR_INVALID_ARG).
Status LoadTrainingViews(const Capture& capture, int frame, const std::vector<int>& cameras,
                         TrainingViews* views);

// Checks that every view has a valid camera and an RGB image of its size.
Status CheckTrainingViews(const TrainingViews& views);

}  // namespace m4d

#endif  // M4D_ENCODER_TRAIN_TRAINING_VIEWS_H_
