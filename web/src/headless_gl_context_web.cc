// In WebAssembly there is no headless GL: the renderer draws into a page's WebGL2 context
// (M4D_RENDER_CURRENT_CONTEXT, m4d_web_renderer.cc). This replaces gl/gl_context.cc there.
#include "sdk/src/gl/gl_context.h"

namespace m4d {

Status CreateHeadlessGlContext(std::unique_ptr<GlContext>*) {
  return Status(M4D_ERR_UNSUPPORTED,
                "no headless GL in WebAssembly: render into the page's WebGL2 context "
                "(M4D_RENDER_CURRENT_CONTEXT)");
}

}  // namespace m4d
