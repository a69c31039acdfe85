// A GaussianSet moved into another world frame by a rotation (axis_rotation.h): positions
// turned, each Gaussian's orientation turned with them (the rotation's quaternion times its
// own) and its view-dependent colour turned too (sh_rotation.h). Scales and opacities stay.
#ifndef M4D_ENCODER_EXPORT_TURN_GAUSSIANS_H_
#define M4D_ENCODER_EXPORT_TURN_GAUSSIANS_H_

#include "encoder/src/export/axis_rotation.h"
#include "sdk/src/layers/gaussian_set.h"

namespace m4d {

// The unit quaternion (w, x, y, z) of a rotation matrix.
void RotationQuaternion(const AxisRotation& r, float q[4]);

// Every Gaussian of *set as seen in the world r * world; nothing to do for the identity.
void TurnGaussians(const AxisRotation& r, GaussianSet* set);

}  // namespace m4d

#endif  // M4D_ENCODER_EXPORT_TURN_GAUSSIANS_H_
