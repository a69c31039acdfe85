// The synthetic scene's camera rig, front-facing like N3DV's: cameras on rows of a
// horizontal arc in front of the room, all aimed at one point inside it. Camera 0, the
// held-out test camera by N3DV's convention, is the one nearest the rig's centre, so views
// interpolated from its neighbours can reach it. With CaptureRealism::sparse_rig the cameras
// stand on one wide arc instead, at head height, and camera 0 is again the one nearest its
// middle.
#ifndef M4D_ENCODER_SYNTHETIC_CAMERA_RIG_H_
#define M4D_ENCODER_SYNTHETIC_CAMERA_RIG_H_

#include <string>
#include <vector>

#include "encoder/src/synthetic/synthetic_scene_options.h"
#include "sdk/src/render/camera.h"

namespace m4d {

// options.cameras cameras at options.width x options.height with square pixels, the
// principal point at the image centre and the horizontal field of view of the options.
std::vector<Camera> MakeCameraRig(const SyntheticSceneOptions& options);

// "cam00", "cam01", ...: zero-padded so that names sort in index order.
std::vector<std::string> CameraNames(int count);

}  // namespace m4d

#endif  // M4D_ENCODER_SYNTHETIC_CAMERA_RIG_H_
