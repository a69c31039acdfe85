// The geometry of one Gaussian under the reference 3DGS model, shared by preprocessing and
// its gradient: camera-space mean, rotation of the normalised quaternion (w, x, y, z),
// scales exp(log_scale), 3D covariance R S S^T R^T, the EWA Jacobian times the camera
// rotation (with X/Z, Y/Z clamped, projection_constants.h) and the dilated 2D covariance.
// Defined once, in the SDK, so that every caller gets the SDK's floating-point behaviour.
#ifndef M4D_SDK_RENDER_SPLAT_GEOMETRY_H_
#define M4D_SDK_RENDER_SPLAT_GEOMETRY_H_

#include "sdk/src/render/projection_constants.h"

namespace m4d {

struct SplatGeometry {
  float view[3];      // camera-space mean
  float rotation[9];  // of the unit quaternion, row-major
  float scale[3];
  float cov3[6];  // xx, xy, xz, yy, yz, zz
  float jw[6];    // J W: row 0 maps to u, row 1 to v
  bool clamped_x, clamped_y;
  float cov2[3];  // a, b, c of [[a, b], [b, c]], with kCovarianceDilation on the diagonal
};

// False (the Gaussian is culled) when the mean is not beyond the near plane, or a value is
// not finite, or the quaternion is zero.
bool ComputeSplatGeometry(const ProjectionConstants& pc, const float position[3],
                          const float log_scale[3], const float quaternion[4], SplatGeometry* g);

}  // namespace m4d

#endif  // M4D_SDK_RENDER_SPLAT_GEOMETRY_H_
