// OffscreenFramebuffer: a framebuffer object with RGBA8 (or half-float RGBA) colour and 24-bit
// depth renderbuffers, multisampled on request, that a headless context renders into, and the
// read-back of its pixels (multisampling resolved, top row first). Half floats keep many
// blended layers from accumulating 8-bit rounding; they need EXT_color_buffer_half_float or
// EXT_color_buffer_float.
#ifndef M4D_SDK_GL_OFFSCREEN_FRAMEBUFFER_H_
#define M4D_SDK_GL_OFFSCREEN_FRAMEBUFFER_H_

#include <cstdint>
#include <memory>
#include <vector>

#include "sdk/src/common/status.h"
#include "sdk/src/gl/gl_functions.h"

namespace m4d {

enum class ColorFormat { kRgba8, kRgba16f };

class OffscreenFramebuffer {
 public:
  // Creates the buffers in the current context, whose function table `gl` must outlive the
  // framebuffer. samples <= 1: no multisampling; larger values are capped at GL_MAX_SAMPLES.
  // M4D_ERR_INVALID_ARG for a size outside 1..GL_MAX_RENDERBUFFER_SIZE, M4D_ERR_UNSUPPORTED
  // when the driver rejects the framebuffer.
  static Status Create(const GlFunctions& gl, int width, int height, int samples,
                       std::unique_ptr<OffscreenFramebuffer>* framebuffer);
  // The same with a colour format; M4D_ERR_UNSUPPORTED when the driver cannot render to it.
  static Status Create(const GlFunctions& gl, int width, int height, int samples,
                       ColorFormat format, std::unique_ptr<OffscreenFramebuffer>* framebuffer);
  // Deletes the GL objects: the context must be current.
  ~OffscreenFramebuffer();
  OffscreenFramebuffer(const OffscreenFramebuffer&) = delete;
  OffscreenFramebuffer& operator=(const OffscreenFramebuffer&) = delete;

  // Binds for drawing and sets the viewport to the whole framebuffer.
  void Bind();
  // Waits for rendering and reads width * height RGBA pixels, row 0 at the top (half floats
  // clamped to [0, 1] and rounded to the nearest byte).
  Status ReadRgba8(std::vector<uint8_t>* rgba);

  int width() const { return width_; }
  int height() const { return height_; }
  int samples() const { return samples_; }
  ColorFormat format() const { return format_; }

 private:
  OffscreenFramebuffer(const GlFunctions& gl, ColorFormat format) : gl_(gl), format_(format) {}
  Status Initialize(int width, int height, int samples);
  Status CreateTarget(int samples, GLuint* framebuffer, GLuint renderbuffers[2]);
  Status ReadPixels(void* pixels);

  const GlFunctions& gl_;
  const ColorFormat format_;
  int width_ = 0;
  int height_ = 0;
  int samples_ = 0;
  GLuint draw_framebuffer_ = 0;  // rendered into; multisampled when samples_ > 1
  GLuint draw_renderbuffers_[2] = {0, 0};
  GLuint resolve_framebuffer_ = 0;  // single-sample copy to read from, when multisampled
  GLuint resolve_renderbuffers_[2] = {0, 0};
};

}  // namespace m4d

#endif  // M4D_SDK_GL_OFFSCREEN_FRAMEBUFFER_H_
