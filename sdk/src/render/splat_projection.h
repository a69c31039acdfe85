// Preprocessing of the rasterizer: per Gaussian, activation of the coded values, EWA
// projection to a 2D splat (mean, conic, radius, covered tiles), SH colour and culling.
//
// Conventions of the reference 3DGS rasterizer, generalised to a principal point:
// - scale = exp(log_scale), opacity = sigmoid(logit), rotation = normalised (w, x, y, z);
// - culled when the camera-space depth is <= near_plane;
// - for the Jacobian, X/Z is clamped to the image's extent in normalised coordinates,
//   [-cx / fx, (width - cx) / fx], widened on each side by 0.3 of its half extent
//   (0.15 width / fx), and likewise Y/Z; with cx = width / 2 this is the reference's
//   +-1.3 tan(fov / 2);
// - the 2D covariance gets 0.3 px^2 added on its diagonal, culled if its determinant is <= 0;
// - radius = ceil(3 sqrt(largest eigenvalue)), the eigenvalue computed as the reference does;
//   a pixel is evaluated only if its centre is within the radius of the mean along x and y;
// - colour = SH + 0.5 in the direction from the camera centre, clamped at 0.
// Also culled (radius 0): Gaussians with any non-finite value, opacity below 1/255 (they
// can never reach the minimum alpha) and splats whose extent misses every pixel centre.
//
// The extent only saves work: alpha >= 1/255 needs d^T conic d <= k^2 = 2 ln(255 opacity),
// an ellipse whose bounding box has half extents k sqrt(cov_xx), k sqrt(cov_yy). The extent is
// that box, with k^2 widened by 0.05 (far beyond float rounding), within the radius square;
// pixels outside it could only be skipped.
#ifndef M4D_RENDER_SPLAT_PROJECTION_H_
#define M4D_RENDER_SPLAT_PROJECTION_H_

#include <cstddef>

#include "render/camera.h"
#include "render/gaussian_layer_view.h"
#include "render/projected_splats.h"

namespace m4d {

constexpr int kTileSize = 16;
constexpr float kCovarianceDilation = 0.3f;
constexpr float kFrustumMargin = 0.15f;  // of the image extent, per side (see above)

// What the projection needs from the camera, computed once per render.
struct ProjectionConstants {
  float rotation[9];
  float translation[3];
  float centre[3];
  float fx, fy, cx, cy;
  float near_plane;
  float limit_x[2], limit_y[2];  // clamp range of X/Z and Y/Z
  int width, height;
  int tiles_x, tiles_y;
};

ProjectionConstants MakeProjectionConstants(const Camera& camera);

// Projects Gaussians [begin, end) of `layer`, evaluating SH up to `sh_degree` (at most the
// layer's), into out at global index offset + i.
void ProjectSplats(const ProjectionConstants& pc, const GaussianLayerView& layer, int sh_degree,
                   size_t begin, size_t end, size_t offset, ProjectedSplats* out);

}  // namespace m4d

#endif  // M4D_RENDER_SPLAT_PROJECTION_H_
