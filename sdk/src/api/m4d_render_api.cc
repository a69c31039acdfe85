// The C API of the renderer (sdk/include/m4d/m4d_render.h) over GlSplatRenderer. Nothing may
// throw through this boundary: allocation failures become M4D_ERR_NOMEM.
#include <cstring>
#include <memory>
#include <new>
#include <string>

#include "m4d/m4d_render.h"
#include "sdk/src/gl/gl_splat_renderer.h"
#include "sdk/src/render/camera.h"

struct M4dRenderer {
  M4dRendererSettings settings;
  std::unique_ptr<m4d::GlSplatRenderer> renderer;
  std::string last_error;
};

namespace {

constexpr uint32_t kDefaultMaxGaussians = 1u << 23;

void Log(const M4dLogger& logger, int level, const std::string& message) {
  if (logger.callback) logger.callback(logger.cookie, level, message.c_str());
}

int Fail(M4dRenderer* r, const m4d::Status& status) {
  r->last_error = status.message();
  Log(r->settings.logger, M4D_LOG_ERROR, status.message());
  return status.code();
}

bool ValidSettings(const M4dRendererSettings* s) {
  for (uint8_t b : s->reserved) {
    if (b != 0) return false;
  }
  for (float c : s->background) {
    if (!(c >= 0.0f && c <= 1.0f)) return false;
  }
  return (s->context == M4D_RENDER_HEADLESS || s->context == M4D_RENDER_CURRENT_CONTEXT) &&
         s->threads >= 0 && s->threads <= 256 && s->sh_degree >= 0 && s->sh_degree <= 3;
}

m4d::Camera ToCamera(const M4dRenderCamera& c) {
  m4d::Camera camera;
  // Sizes beyond int's range are clamped to fail ValidateCamera rather than wrap.
  camera.width = static_cast<int>(c.width > 1u << 30 ? 1u << 30 : c.width);
  camera.height = static_cast<int>(c.height > 1u << 30 ? 1u << 30 : c.height);
  camera.fx = c.fx;
  camera.fy = c.fy;
  camera.cx = c.cx;
  camera.cy = c.cy;
  std::memcpy(camera.rotation, c.rotation, sizeof(camera.rotation));
  std::memcpy(camera.translation, c.translation, sizeof(camera.translation));
  camera.near_plane = c.near_plane;
  return camera;
}

bool ConsistentLayer(const M4dGaussians& g) {
  if (g.count == 0) return true;
  return g.sh_degree <= 3 && g.sh_coefficients == (g.sh_degree + 1) * (g.sh_degree + 1);
}

}  // namespace

extern "C" {

void m4d_renderer_default_settings(M4dRendererSettings* s) {
  if (!s) return;
  std::memset(s, 0, sizeof(*s));
  s->context = M4D_RENDER_HEADLESS;
  s->sh_degree = 3;
}

int m4d_renderer_open(M4dRenderer** r_out, const M4dRendererSettings* s) {
  if (!r_out) return M4D_ERR_INVALID_ARG;
  *r_out = nullptr;
  if (!s || !ValidSettings(s)) return M4D_ERR_INVALID_ARG;
  M4dRenderer* r = new (std::nothrow) M4dRenderer();
  if (!r) return M4D_ERR_NOMEM;
  r->settings = *s;
  m4d::GlRendererOptions options;
  options.headless = s->context == M4D_RENDER_HEADLESS;
  options.loader = s->get_proc_address;
  options.threads = s->threads;
  options.sh_degree = s->sh_degree;
  options.max_gaussians = s->max_gaussians ? s->max_gaussians : kDefaultMaxGaussians;
  std::memcpy(options.background, s->background, sizeof(options.background));
  try {
    const m4d::Status status = m4d::GlSplatRenderer::Create(options, &r->renderer);
    if (!status.ok()) {
      Log(s->logger, M4D_LOG_ERROR, status.message());
      delete r;
      return status.code();
    }
  } catch (const std::bad_alloc&) {
    delete r;
    return M4D_ERR_NOMEM;
  }
  Log(s->logger, M4D_LOG_INFO, "renderer: " + r->renderer->description());
  *r_out = r;
  return M4D_OK;
}

int m4d_renderer_upload(M4dRenderer* r, const M4dFrame* frame, uint32_t layers) {
  if (!r) return M4D_ERR_INVALID_ARG;
  if (!frame || (layers & ~M4D_LAYER_ALL) != 0) {
    return Fail(r, m4d::Status(M4D_ERR_INVALID_ARG, "renderer: null frame or unknown layers"));
  }
  M4dGaussians views[2];
  int count = 0;
  const uint32_t wanted = layers & frame->layers;
  for (const M4dGaussians* g : {&frame->static_layer, &frame->dynamic_layer}) {
    const uint32_t bit = g == &frame->static_layer ? M4D_LAYER_STATIC : M4D_LAYER_DYNAMIC;
    if (!(wanted & bit) || g->count == 0) continue;
    if (!ConsistentLayer(*g)) {
      return Fail(r, m4d::Status(M4D_ERR_INVALID_ARG, "renderer: inconsistent SH layout"));
    }
    views[count++] = *g;
  }
  try {
    const m4d::Status status = r->renderer->Upload(views, count);
    if (!status.ok()) return Fail(r, status);
  } catch (const std::bad_alloc&) {
    return Fail(r, m4d::Status(M4D_ERR_NOMEM, "renderer: out of memory copying the frame"));
  }
  return M4D_OK;
}

int m4d_renderer_draw(M4dRenderer* r, const M4dRenderCamera* camera) {
  if (!r) return M4D_ERR_INVALID_ARG;
  if (!camera) return Fail(r, m4d::Status(M4D_ERR_INVALID_ARG, "renderer: null camera"));
  for (uint8_t b : camera->reserved) {  // zero, as in the settings: room for later fields
    if (b != 0) {
      return Fail(r, m4d::Status(M4D_ERR_INVALID_ARG, "renderer: non-zero reserved camera bytes"));
    }
  }
  try {
    const m4d::Status status = r->renderer->Draw(ToCamera(*camera));
    if (!status.ok()) return Fail(r, status);
  } catch (const std::bad_alloc&) {
    return Fail(r, m4d::Status(M4D_ERR_NOMEM, "renderer: out of memory"));
  }
  return M4D_OK;
}

int m4d_renderer_read_rgb(M4dRenderer* r, uint8_t* rgb, size_t size) {
  if (!r) return M4D_ERR_INVALID_ARG;
  try {
    const m4d::Status status = r->renderer->ReadRgb(rgb, size);
    if (!status.ok()) return Fail(r, status);
  } catch (const std::bad_alloc&) {
    return Fail(r, m4d::Status(M4D_ERR_NOMEM, "renderer: out of memory"));
  }
  return M4D_OK;
}

int m4d_renderer_stats(const M4dRenderer* r, M4dRenderStats* stats) {
  if (!r || !stats) return M4D_ERR_INVALID_ARG;
  const m4d::GlRenderTimings& t = r->renderer->timings();
  std::memset(stats, 0, sizeof(*stats));
  stats->visible = static_cast<uint32_t>(t.visible);
  stats->project_ms = t.project_ms;
  stats->sort_ms = t.sort_ms;
  stats->upload_ms = t.upload_ms;
  stats->draw_ms = t.draw_ms;
  return M4D_OK;
}

const char* m4d_renderer_last_error(const M4dRenderer* r) { return r ? r->last_error.c_str() : ""; }

const char* m4d_renderer_description(const M4dRenderer* r) {
  return r ? r->renderer->description().c_str() : "";
}

void m4d_renderer_close(M4dRenderer** r) {
  if (!r || !*r) return;
  delete *r;
  *r = nullptr;
}

}  // extern "C"
