// The WebAssembly module's renderer: the SDK's OpenGL ES 3.0 splat renderer (m4d_render.h)
// drawing into a page's WebGL2 canvas, which it makes its current context. WebGL2 is
// OpenGL ES 3.0, so the shaders and the CPU stages (projection, SH colour, depth sort) are
// the native renderer's. JavaScript (web/js/m4d.mjs) fills the camera and calls these.
#include <emscripten/emscripten.h>
#include <emscripten/html5.h>

#include <new>

#include "m4d/m4d_render.h"
#include "web/src/m4d_web_stream.h"

struct M4dWebRenderer {
  EMSCRIPTEN_WEBGL_CONTEXT_HANDLE webgl = 0;
  M4dRenderer* renderer = nullptr;
  M4dRenderCamera camera = {};
  M4dRenderStats stats = {};
};

namespace {

void (*WebGlProcAddress(const char* name))(void) {
  return reinterpret_cast<void (*)(void)>(emscripten_webgl_get_proc_address(name));
}

}  // namespace

extern "C" {

// Creates a WebGL2 context on the canvas that `selector` names (e.g. "#view"; with
// preserveDrawingBuffer, so a drawn frame can be read back) and the SDK's renderer in it,
// drawing behind the splats the colour `background` (linear RGB), evaluating SH up to
// `sh_degree`. Returns NULL when WebGL2 or the renderer is not available.
EMSCRIPTEN_KEEPALIVE M4dWebRenderer* m4dw_renderer_open(const char* selector, float red,
                                                        float green, float blue, int sh_degree) {
  EmscriptenWebGLContextAttributes attributes;
  emscripten_webgl_init_context_attributes(&attributes);
  attributes.majorVersion = 2;
  attributes.alpha = true;  // the splats blend front to back on destination alpha
  attributes.depth = false;
  attributes.antialias = false;
  attributes.preserveDrawingBuffer = true;
  const EMSCRIPTEN_WEBGL_CONTEXT_HANDLE webgl =
      emscripten_webgl_create_context(selector, &attributes);
  if (webgl <= 0) return nullptr;
  M4dWebRenderer* r = new (std::nothrow) M4dWebRenderer;
  if (r == nullptr || emscripten_webgl_make_context_current(webgl) != EMSCRIPTEN_RESULT_SUCCESS) {
    delete r;
    emscripten_webgl_destroy_context(webgl);
    return nullptr;
  }
  r->webgl = webgl;
  M4dRendererSettings settings;
  m4d_renderer_default_settings(&settings);
  settings.context = M4D_RENDER_CURRENT_CONTEXT;
  settings.get_proc_address = WebGlProcAddress;
  settings.threads = 1;
  settings.sh_degree = sh_degree;
  settings.background[0] = red;
  settings.background[1] = green;
  settings.background[2] = blue;
  if (m4d_renderer_open(&r->renderer, &settings) < 0) {
    emscripten_webgl_destroy_context(webgl);
    delete r;
    return nullptr;
  }
  return r;
}

// The camera m4dw_renderer_draw uses (M4dRenderCamera), for JavaScript to fill.
EMSCRIPTEN_KEEPALIVE M4dRenderCamera* m4dw_renderer_camera(M4dWebRenderer* r) { return &r->camera; }

// Uploads the `layers` (M4D_LAYER_* bits) of the frame the reader holds.
EMSCRIPTEN_KEEPALIVE int m4dw_renderer_upload(M4dWebRenderer* r, const M4dWebStream* s,
                                              uint32_t layers) {
  if (r == nullptr || s == nullptr || !s->holding_frame) return M4D_ERR_INVALID_ARG;
  return m4d_renderer_upload(r->renderer, &s->frame, layers);
}

// Draws the uploaded Gaussians into the canvas with the camera (viewport: the canvas's).
EMSCRIPTEN_KEEPALIVE int m4dw_renderer_draw(M4dWebRenderer* r) {
  if (r == nullptr) return M4D_ERR_INVALID_ARG;
  emscripten_webgl_make_context_current(r->webgl);
  return m4d_renderer_draw(r->renderer, &r->camera);
}

// The last draw's timings (M4dRenderStats), for JavaScript to read.
EMSCRIPTEN_KEEPALIVE const M4dRenderStats* m4dw_renderer_stats(M4dWebRenderer* r) {
  m4d_renderer_stats(r->renderer, &r->stats);
  return &r->stats;
}

EMSCRIPTEN_KEEPALIVE const char* m4dw_renderer_last_error(const M4dWebRenderer* r) {
  return m4d_renderer_last_error(r->renderer);
}

// Closes the renderer and its WebGL context.
EMSCRIPTEN_KEEPALIVE void m4dw_renderer_close(M4dWebRenderer* r) {
  if (r == nullptr) return;
  emscripten_webgl_make_context_current(r->webgl);
  m4d_renderer_close(&r->renderer);
  emscripten_webgl_destroy_context(r->webgl);
  delete r;
}

}  // extern "C"
