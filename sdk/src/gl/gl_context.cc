#include "sdk/src/gl/gl_context.h"

#include "sdk/src/gl/egl_context.h"
#include "sdk/src/gl/osmesa_context.h"

namespace m4d {

Status CreateHeadlessGlContext(std::unique_ptr<GlContext>* context) {
  std::unique_ptr<EglContext> egl;
  const Status egl_status = EglContext::Create(&egl);
  if (egl_status.ok()) {
    *context = std::move(egl);
    return Status::Ok();
  }
  std::unique_ptr<OsmesaContext> osmesa;
  const Status osmesa_status = OsmesaContext::Create(&osmesa);
  if (osmesa_status.ok()) {
    *context = std::move(osmesa);
    return Status::Ok();
  }
  return Status(M4D_ERR_UNSUPPORTED, "no headless OpenGL ES context: " + egl_status.message() +
                                         "; " + osmesa_status.message());
}

}  // namespace m4d
