// EglContext: a headless OpenGL ES 3.0 context through EGL, for rendering into framebuffer
// objects without a window or a GPU (Mesa's llvmpipe works). The display comes from Mesa's
// surfaceless platform when the EGL library offers it, else from EGL_DEFAULT_DISPLAY with a
// 1x1 pbuffer to be current on. Owns its context and its GL function table; no global state.
#ifndef M4D_SDK_GL_EGL_CONTEXT_H_
#define M4D_SDK_GL_EGL_CONTEXT_H_

#include <memory>
#include <string>

#include "sdk/src/common/status.h"
#include "sdk/src/gl/gl_context.h"
#include "sdk/src/gl/gl_functions.h"

namespace m4d {

class EglContext : public GlContext {
 public:
  // Creates the context and makes it current on the calling thread. M4D_ERR_UNSUPPORTED with
  // the reason when no display, no GLES 3 configuration or no context is available.
  static Status Create(std::unique_ptr<EglContext>* context);
  ~EglContext() override;
  EglContext(const EglContext&) = delete;
  EglContext& operator=(const EglContext&) = delete;

  // A context is current on one thread at a time; GL calls go to the current one.
  Status MakeCurrent() override;
  void ReleaseCurrent() override;

  const GlFunctions& gl() const override { return gl_; }
  // Which display kind was used and the GL renderer, e.g. "surfaceless, llvmpipe (...)".
  const std::string& description() const override { return description_; }

 private:
  EglContext() = default;
  Status Initialize();

  // EGLDisplay, EGLContext and EGLSurface are opaque pointers; kept as void* so that this
  // header does not pull in the EGL (and window-system) headers.
  void* display_ = nullptr;
  void* context_ = nullptr;
  void* surface_ = nullptr;  // the pbuffer, or null when current without a surface
  GlFunctions gl_;
  std::string description_;
};

}  // namespace m4d

#endif  // M4D_SDK_GL_EGL_CONTEXT_H_
