// Preprocessing of the rasterizer: per Gaussian, the EWA projection to a 2D splat (mean,
// conic, radius, extent, covered tiles), its opacity and SH colour, and culling. Conventions
// of the reference 3DGS rasterizer (see also splat_geometry.h, projection_constants.h):
// - opacity = sigmoid(logit); culled when the camera-space depth is <= the near plane;
// - the dilated 2D covariance is culled if its determinant is <= 0; conic = its inverse;
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
#ifndef M4D_SDK_RENDER_SPLAT_PROJECTION_H_
#define M4D_SDK_RENDER_SPLAT_PROJECTION_H_

#include <cstddef>

#include "sdk/src/layers/gaussian_views.h"
#include "sdk/src/render/projected_splats.h"
#include "sdk/src/render/projection_constants.h"

namespace m4d {

// Projects Gaussians [begin, end) of `layer`, evaluating SH up to `sh_degree` (at most the
// layer's), into out at global index offset + i.
void ProjectSplats(const ProjectionConstants& pc, const M4dGaussians& layer, int sh_degree,
                   size_t begin, size_t end, size_t offset, ProjectedSplats* out);

}  // namespace m4d

#endif  // M4D_SDK_RENDER_SPLAT_PROJECTION_H_
