// Left-handed calibrations. Some calibration tools write world-to-camera rotations that are
// orthonormal with determinant -1: the world frame is a mirror image of a right-handed one.
// Projection is unchanged if the whole world is mirrored consistently, so the capture is
// converted to the right-handed world x' = (-x, y, z): every camera's rotation gets its first
// column negated (R' = R diag(-1, 1, 1)) and every initial point its x negated. Images are
// untouched. Everything the encoder writes (streams, PLY files) is in that mirrored world;
// negate x to go back to the calibration's frame.
#ifndef M4D_ENCODER_DATASET_WORLD_HANDEDNESS_H_
#define M4D_ENCODER_DATASET_WORLD_HANDEDNESS_H_

#include "encoder/src/capture/capture.h"
#include "sdk/src/common/status.h"

namespace m4d {

// Determinant of a row-major 3x3 rotation, in double.
double RotationDeterminant(const float rotation[9]);

// Mirrors the capture's world when every camera of every frame is left-handed (and adds a
// note); leaves a right-handed capture alone. M4D_ERR_INVALID_ARG naming the cameras when
// the handedness differs between cameras (no single world explains such a calibration).
Status MakeWorldRightHanded(Capture* capture);

// The mirror itself: the camera that sees the mirrored world x' = (-x, y, z) as `camera` sees
// the world (its rotation's first column negated), and points with x negated.
Camera MirrorWorldX(const Camera& camera);
void MirrorWorldX(PointCloud* points);

}  // namespace m4d

#endif  // M4D_ENCODER_DATASET_WORLD_HANDEDNESS_H_
