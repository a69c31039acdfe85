// GlContext: a headless OpenGL ES 3.0 (or ES 3.0 compatible) context the SDK owns, whatever
// made it (EGL, or OSMesa as a fallback): make it current, call GL through its function table.
#ifndef M4D_SDK_GL_GL_CONTEXT_H_
#define M4D_SDK_GL_GL_CONTEXT_H_

#include <memory>
#include <string>

#include "sdk/src/common/status.h"
#include "sdk/src/gl/gl_functions.h"

namespace m4d {

class GlContext {
 public:
  virtual ~GlContext() = default;
  // A context is current on one thread at a time; GL calls go to the current one.
  virtual Status MakeCurrent() = 0;
  virtual void ReleaseCurrent() = 0;
  virtual const GlFunctions& gl() const = 0;
  // Which platform made it and the GL renderer, e.g. "EGL surfaceless, llvmpipe (...)".
  virtual const std::string& description() const = 0;
};

// An EGL context (egl_context.h), else an OSMesa one (osmesa_context.h); current on the
// calling thread. M4D_ERR_UNSUPPORTED with both reasons when neither can be made.
Status CreateHeadlessGlContext(std::unique_ptr<GlContext>* context);

}  // namespace m4d

#endif  // M4D_SDK_GL_GL_CONTEXT_H_
