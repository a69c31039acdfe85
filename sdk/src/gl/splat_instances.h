// SplatInstances: the CPU half of the GL renderer. Every Gaussian is projected with the
// reference rasterizer's preprocessing (render/splat_projection.h: the same EWA projection,
// culling, opacity and SH colour per view), the visible splats are sorted front to back by
// camera-space depth (radix sort on the float bits; ties keep the concatenation order, like
// the reference's stable sort), and each becomes one instance record for the vertex shader.
#ifndef M4D_SDK_GL_SPLAT_INSTANCES_H_
#define M4D_SDK_GL_SPLAT_INSTANCES_H_

#include <cstddef>
#include <cstdint>
#include <vector>

#include "sdk/src/common/status.h"
#include "sdk/src/common/thread_pool.h"
#include "sdk/src/layers/gaussian_views.h"
#include "sdk/src/render/camera.h"
#include "sdk/src/render/projected_splats.h"

namespace m4d {

// One splat as the vertex shader reads it (three vec4 attributes). The splat is drawn as the
// rectangle around the ellipse where its alpha can reach 1/255, d^T conic d <= k^2 with
// k^2 = 2 ln(255 opacity) (+0.05, as the reference's extent), laid along the ellipse's axes:
// fewer fragments than the axis-aligned box for elongated, tilted splats.
struct SplatInstance {
  float mean[2];    // projected mean (u, v) in pixels, row 0 at the top
  float axis[2];    // the ellipse's major half axis at k, in pixels
  float minor;      // its minor half length at k, in pixels
  float k;          // the ellipse's size in standard deviations
  float extent[2];  // the reference's visited box: |pixel - mean| <= extent along u and v
  float color[3];   // SH colour + 0.5, clamped at 0
  float opacity;
};
static_assert(sizeof(SplatInstance) == 12 * sizeof(float), "three vec4 per instance");

struct SplatInstanceTimings {
  double project_ms = 0;
  double sort_ms = 0;
};

class SplatInstanceBuilder {
 public:
  // threads: CPU workers including the caller (0: all cores).
  explicit SplatInstanceBuilder(int threads) : pool_(threads) {}

  // Fills *instances, front to back, for the layers seen from camera (SH up to sh_degree).
  // M4D_ERR_INVALID_ARG for a bad camera (ValidateCamera) or SH degree.
  Status Build(const Camera& camera, const M4dGaussians* layers, int layer_count, int sh_degree,
               std::vector<SplatInstance>* instances, SplatInstanceTimings* timings);

 private:
  ThreadPool pool_;
  ProjectedSplats projected_;
  std::vector<uint32_t> keys_, order_, key_scratch_, order_scratch_;
};

}  // namespace m4d

#endif  // M4D_SDK_GL_SPLAT_INSTANCES_H_
