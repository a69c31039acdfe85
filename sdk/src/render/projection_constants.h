// ProjectionConstants: what projecting Gaussians needs from the camera, computed once per
// render and shared by the forward and backward passes.
//
// The EWA Jacobian clamps X/Z and Y/Z like the reference 3DGS rasterizer, generalised to a
// principal point: X/Z is clamped to the image's extent in normalised coordinates,
// [-cx / fx, (width - cx) / fx], widened on each side by 0.3 of its half extent
// (kFrustumMargin = 0.15 of the width, over fx); likewise Y/Z. With cx = width / 2 this is
// the reference's +-1.3 tan(fov_x / 2).
#ifndef M4D_SDK_RENDER_PROJECTION_CONSTANTS_H_
#define M4D_SDK_RENDER_PROJECTION_CONSTANTS_H_

#include "sdk/src/render/camera.h"

namespace m4d {

constexpr int kTileSize = 16;
constexpr float kCovarianceDilation = 0.3f;  // px^2 added to the 2D covariance's diagonal
constexpr float kFrustumMargin = 0.15f;      // of the image extent, per side

struct ProjectionConstants {
  float rotation[9];  // world to camera, row-major
  float translation[3];
  float centre[3];  // camera centre in world coordinates
  float fx, fy, cx, cy;
  float near_plane;
  float limit_x[2], limit_y[2];  // clamp range of X/Z and Y/Z
  int width, height;
  int tiles_x, tiles_y;
};

ProjectionConstants MakeProjectionConstants(const Camera& camera);

}  // namespace m4d

#endif  // M4D_SDK_RENDER_PROJECTION_CONSTANTS_H_
