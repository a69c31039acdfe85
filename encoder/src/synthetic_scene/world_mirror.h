// The left-handed calibration of the realistic synthetic scene (CaptureRealism::left_handed):
// the world mirrored through the plane x = 0, as some calibration tools leave it. Images do
// not change; camera poses get rotations of determinant -1.
#ifndef M4D_ENCODER_SYNTHETIC_SCENE_WORLD_MIRROR_H_
#define M4D_ENCODER_SYNTHETIC_SCENE_WORLD_MIRROR_H_

#include "dataset/point_cloud.h"
#include "render/camera.h"

namespace m4d {

// The camera that sees the mirrored world as `camera` sees the world: x_cam = R M x + t with
// M = diag(-1, 1, 1), i.e. the rotation's first column negated.
Camera MirrorWorldX(const Camera& camera);

// Negates every point's x.
void MirrorWorldX(PointCloud* points);

}  // namespace m4d

#endif  // M4D_ENCODER_SYNTHETIC_SCENE_WORLD_MIRROR_H_
