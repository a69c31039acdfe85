// Camera: a pinhole camera with OpenCV axes (x right, y down, z forward) and a
// world-to-camera rigid transform, x_cam = R x_world + t.
//
// Pixel convention (COLMAP's): a camera-space point projects to u = fx X / Z + cx,
// v = fy Y / Z + cy; the image spans [0, width] x [0, height] in (u, v), and pixel (i, j) (column
// i, row j, row 0 at the top) has its centre at (i + 0.5, j + 0.5). With cx = width / 2 this is
// the pixel grid of the reference 3DGS rasterizer (whose pixel i sits at ndc2Pix = i).
#ifndef M4D_SDK_RENDER_CAMERA_H_
#define M4D_SDK_RENDER_CAMERA_H_

#include "sdk/src/common/status.h"

namespace m4d {

// Largest image side the renderer accepts, and largest pixel count.
constexpr int kMaxImageSide = 16384;
constexpr long long kMaxImagePixels = 1ll << 26;

struct Camera {
  int width = 0;
  int height = 0;
  float fx = 0, fy = 0;  // focal lengths in pixels
  float cx = 0, cy = 0;  // principal point in pixels (image centre: width / 2, height / 2)
  // World-to-camera rotation, row-major, and translation.
  float rotation[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  float translation[3] = {0, 0, 0};
  // Gaussians whose camera-space depth is <= near_plane are culled (the reference uses 0.2).
  float near_plane = 0.2f;
};

// Checks sizes (1..kMaxImageSide, at most kMaxImagePixels), finite positive focal lengths,
// finite principal point and transform, an orthonormal rotation (to 1e-3) and a positive
// near plane.
Status ValidateCamera(const Camera& camera);

// The camera centre in world coordinates, -R^T t.
void CameraCentre(const Camera& camera, float centre[3]);

}  // namespace m4d

#endif  // M4D_SDK_RENDER_CAMERA_H_
