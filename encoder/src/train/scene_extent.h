// The scene's size as the reference 3DGS measures it from the training cameras: 1.1 times
// the largest distance of a camera centre from their mean. It scales the position learning
// rate and the densification thresholds; random initialisation fills the box of that
// half-size around the mean centre.
#ifndef M4D_ENCODER_TRAIN_SCENE_EXTENT_H_
#define M4D_ENCODER_TRAIN_SCENE_EXTENT_H_

#include <vector>

#include "sdk/src/render/camera.h"

namespace m4d {

struct SceneBounds {
  float centre[3] = {0, 0, 0};  // mean camera centre
  float extent = 0;             // 1.1 x the largest distance of a camera centre from it
};

// Zero extent for fewer than two distinct camera centres.
SceneBounds CameraSceneBounds(const std::vector<Camera>& cameras);

}  // namespace m4d

#endif  // M4D_ENCODER_TRAIN_SCENE_EXTENT_H_
