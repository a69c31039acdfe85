// OsmesaContext: the fallback headless context when EGL offers none: Mesa's off-screen
// library, opened at run time (dlopen of libOSMesa), so the SDK neither links against it nor
// needs it installed. It makes a desktop OpenGL 3.3 core context; the renderer's shaders are
// GLSL ES 3.00, which Mesa's desktop contexts accept (ARB_ES3_compatibility). Rendering goes
// to framebuffer objects; OSMesa's own 1x1 buffer only makes the context current.
#ifndef M4D_SDK_GL_OSMESA_CONTEXT_H_
#define M4D_SDK_GL_OSMESA_CONTEXT_H_

#include <memory>
#include <string>

#include "sdk/src/common/status.h"
#include "sdk/src/gl/gl_context.h"
#include "sdk/src/gl/gl_functions.h"

namespace m4d {

class OsmesaContext : public GlContext {
 public:
  // Creates the context and makes it current. M4D_ERR_UNSUPPORTED with the reason when the
  // library or a GL 3.3 core context with ES 3 compatibility is not available.
  static Status Create(std::unique_ptr<OsmesaContext>* context);
  ~OsmesaContext() override;
  OsmesaContext(const OsmesaContext&) = delete;
  OsmesaContext& operator=(const OsmesaContext&) = delete;

  Status MakeCurrent() override;
  void ReleaseCurrent() override;
  const GlFunctions& gl() const override { return gl_; }
  const std::string& description() const override { return description_; }

 private:
  OsmesaContext() = default;
  Status Initialize();

  void* library_ = nullptr;  // dlopen handle
  void* context_ = nullptr;  // OSMesaContext
  unsigned char buffer_[4] = {0, 0, 0, 0};
  GlFunctions gl_;
  std::string description_;
};

}  // namespace m4d

#endif  // M4D_SDK_GL_OSMESA_CONTEXT_H_
