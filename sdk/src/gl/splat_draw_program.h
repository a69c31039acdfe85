// SplatDrawProgram: the GL half of the renderer. One instanced quad per splat, laid along the
// axes of its ellipse (splat_instances.h); the fragment shader evaluates the reference rasterizer's
// alpha at the pixel centre (render/splat_alpha.h: power, the 0.99 cap, the 1/255 cut, and the
// reference's visited box around the mean) and outputs premultiplied colour, blended front to back
// ("under": dst += (1 - dst_alpha) src) into a target cleared to zero; a last full-viewport quad
// composites the background the same way, so the result is C + T_final * background as in the
// reference. Unlike the reference, a pixel does not stop once its transmittance falls below 1e-4
// (what it would skip weighs less than that; chunked early termination through the depth test was
// tried and saved nothing on llvmpipe, where most overdraw is the many layers of one surface rather
// than hidden surfaces).
#ifndef M4D_SDK_GL_SPLAT_DRAW_PROGRAM_H_
#define M4D_SDK_GL_SPLAT_DRAW_PROGRAM_H_

#include <cstddef>
#include <memory>

#include "sdk/src/common/status.h"
#include "sdk/src/gl/gl_functions.h"
#include "sdk/src/gl/splat_instances.h"

namespace m4d {

class SplatDrawProgram {
 public:
  // Compiles the shaders and creates the buffers in the current context; `gl` must outlive
  // the program.
  static Status Create(const GlFunctions& gl, std::unique_ptr<SplatDrawProgram>* program);
  // Deletes the GL objects: the context must be current.
  ~SplatDrawProgram();
  SplatDrawProgram(const SplatDrawProgram&) = delete;
  SplatDrawProgram& operator=(const SplatDrawProgram&) = delete;

  // Uploads the instances (front to back) into the instance buffer.
  void Upload(const SplatInstance* instances, size_t count);
  // Draws the uploaded splats and the background into the bound draw framebuffer, whose
  // viewport (x, y, width, height) the camera's image fills. Clears it first when `clear`.
  void Draw(const int viewport[4], const float background[3], bool clear);

 private:
  explicit SplatDrawProgram(const GlFunctions& gl) : gl_(gl) {}
  Status Initialize();

  const GlFunctions& gl_;
  GLuint program_ = 0;
  GLuint background_program_ = 0;
  GLuint vertex_array_ = 0;
  GLuint empty_vertex_array_ = 0;
  GLuint instance_buffer_ = 0;
  GLint viewport_location_ = -1;
  GLint background_location_ = -1;
  size_t count_ = 0;
};

}  // namespace m4d

#endif  // M4D_SDK_GL_SPLAT_DRAW_PROGRAM_H_
