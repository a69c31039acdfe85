// Background shell: initial points for what a capture's surroundings show (a dome's wall, a
// room's plain walls), which carry no point of their own: a plane sweep cannot place a ray
// through uniform colour (photo_consistent_points.h), and Gaussians that training grows there
// fit each view at a wrong depth and misplace the wall in views not trained on. The shell is
// a sphere around the point the cameras look at (least squares over their optical axes) with
// the cameras' median distance to it as radius: on a dome the cameras hang on the wall, and in
// front of a rig it stands behind the content. Points spread evenly over it (a Fibonacci
// sphere); each seen by min_views views is kept with their mean colour.
#ifndef M4D_ENCODER_TRAIN_BACKGROUND_SHELL_H_
#define M4D_ENCODER_TRAIN_BACKGROUND_SHELL_H_

#include <cstddef>

#include "encoder/src/capture/point_cloud.h"
#include "encoder/src/train/training_views.h"
#include "sdk/src/common/status.h"

namespace m4d {

struct BackgroundShellOptions {
  size_t points = 20000;      // spread over the whole sphere; those no view sees are dropped
  float radius_scale = 1.0f;  // times the cameras' median distance to the centre
  int min_views = 2;
};

struct BackgroundShell {
  float centre[3] = {0, 0, 0};
  float radius = 0;
};

// The sphere of the cameras (no radius for fewer than two cameras or parallel axes).
BackgroundShell CameraShell(const TrainingViews& views, float radius_scale);

// M4D_ERR_INVALID_ARG for no views or bad options; no points when the cameras give no shell.
Status BackgroundShellPoints(const TrainingViews& views, const BackgroundShellOptions& options,
                             PointCloud* points);

}  // namespace m4d

#endif  // M4D_ENCODER_TRAIN_BACKGROUND_SHELL_H_
