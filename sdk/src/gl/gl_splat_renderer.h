// GlSplatRenderer: the SDK's OpenGL ES renderer behind m4d_render.h. It owns copies of the
// uploaded layers, the CPU stage (splat_instances.h) and the GL stage (splat_draw_program.h),
// and either its own headless context and framebuffer or nothing of the caller's but the GL
// objects it creates in the caller's current context.
#ifndef M4D_SDK_GL_GL_SPLAT_RENDERER_H_
#define M4D_SDK_GL_GL_SPLAT_RENDERER_H_

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "sdk/src/common/status.h"
#include "sdk/src/gl/gl_context.h"
#include "sdk/src/gl/gl_functions.h"
#include "sdk/src/gl/offscreen_framebuffer.h"
#include "sdk/src/gl/splat_draw_program.h"
#include "sdk/src/gl/splat_instances.h"
#include "sdk/src/layers/gaussian_set.h"
#include "sdk/src/layers/gaussian_views.h"
#include "sdk/src/render/camera.h"

namespace m4d {

struct GlRendererOptions {
  bool headless = true;
  GlProcLoader loader = nullptr;  // the caller's context (not headless); null: EGL's
  int threads = 0;
  int sh_degree = 3;
  size_t max_gaussians = size_t{1} << 23;
  float background[3] = {0, 0, 0};
};

struct GlRenderTimings {
  size_t visible = 0;
  double project_ms = 0, sort_ms = 0, upload_ms = 0, draw_ms = 0;
};

class GlSplatRenderer {
 public:
  // Headless: makes the context (current on the calling thread). Otherwise the caller's
  // context must be current. M4D_ERR_UNSUPPORTED when GL is missing or too old.
  static Status Create(const GlRendererOptions& options, std::unique_ptr<GlSplatRenderer>* out);
  // In the current context, whose entry points `gl` already holds (options.headless and
  // options.loader are ignored).
  static Status CreateWithFunctions(const GlRendererOptions& options, const GlFunctions& gl,
                                    std::unique_ptr<GlSplatRenderer>* out);
  ~GlSplatRenderer();
  GlSplatRenderer(const GlSplatRenderer&) = delete;
  GlSplatRenderer& operator=(const GlSplatRenderer&) = delete;

  // Copies the layers (checked: arrays present, SH degree 0..3, count within the limit).
  Status Upload(const M4dGaussians* layers, int layer_count);
  Status Draw(const Camera& camera);
  // The last headless draw, RGB bytes, row 0 at the top.
  Status ReadRgb(uint8_t* rgb, size_t size);

  const GlRenderTimings& timings() const { return timings_; }
  const std::string& description() const { return description_; }

 private:
  explicit GlSplatRenderer(const GlRendererOptions& options)
      : options_(options), instances_builder_(options.threads) {}
  Status Initialize(const GlFunctions* loaded);
  Status HeadlessTarget(int width, int height);

  GlRendererOptions options_;
  std::unique_ptr<GlContext> context_;  // headless only
  GlFunctions caller_gl_;               // the caller's context's table
  const GlFunctions* gl_ = nullptr;
  std::unique_ptr<SplatDrawProgram> program_;
  // Headless only. RGBA8: faster to blend on llvmpipe than half floats, agrees closely with the CPU
  // reference (docs/results/2026-11-30-comment-measurements.md), and its alpha reaching exactly 1
  // is what early termination tests.
  std::unique_ptr<OffscreenFramebuffer> framebuffer_;
  SplatInstanceBuilder instances_builder_;
  std::vector<SplatInstance> instances_;
  std::vector<GaussianSet> layers_;
  bool drawn_ = false;
  GlRenderTimings timings_;
  std::string description_;
  std::vector<uint8_t> rgba_;
};

}  // namespace m4d

#endif  // M4D_SDK_GL_GL_SPLAT_RENDERER_H_
