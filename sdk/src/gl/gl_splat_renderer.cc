#include "sdk/src/gl/gl_splat_renderer.h"

#define EGL_NO_X11 1
#include <EGL/egl.h>

#include <chrono>
#include <cstring>

namespace m4d {
namespace {

using Clock = std::chrono::steady_clock;

double MillisecondsSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

Status CheckLayer(const M4dGaussians& layer) {
  if (layer.sh_degree > 3) {
    return Status(M4D_ERR_INVALID_ARG, "renderer: SH degree must be 0..3");
  }
  if (layer.count > 0 && (!layer.positions || !layer.log_scales || !layer.rotations ||
                          !layer.opacity_logits || !layer.sh)) {
    return Status(M4D_ERR_INVALID_ARG, "renderer: a layer has a null array");
  }
  return Status::Ok();
}

void CopyLayer(const M4dGaussians& from, GaussianSet* to) {
  to->sh_degree = from.sh_degree;
  to->Resize(from.count);
  if (from.count == 0) return;
  std::memcpy(to->positions.data(), from.positions, 3 * from.count * sizeof(float));
  std::memcpy(to->log_scales.data(), from.log_scales, 3 * from.count * sizeof(float));
  std::memcpy(to->rotations.data(), from.rotations, 4 * from.count * sizeof(float));
  std::memcpy(to->opacity_logits.data(), from.opacity_logits, from.count * sizeof(float));
  std::memcpy(to->sh.data(), from.sh, to->sh.size() * sizeof(float));
}

}  // namespace

namespace {

Status CheckOptions(const GlRendererOptions& options) {
  if (options.sh_degree < 0 || options.sh_degree > 3 || options.threads < 0) {
    return Status(M4D_ERR_INVALID_ARG, "renderer: SH degree must be 0..3, threads >= 0");
  }
  return Status::Ok();
}

}  // namespace

Status GlSplatRenderer::Create(const GlRendererOptions& options,
                               std::unique_ptr<GlSplatRenderer>* out) {
  M4D_RETURN_IF_ERROR(CheckOptions(options));
  std::unique_ptr<GlSplatRenderer> created(new GlSplatRenderer(options));
  M4D_RETURN_IF_ERROR(created->Initialize(nullptr));
  *out = std::move(created);
  return Status::Ok();
}

Status GlSplatRenderer::CreateWithFunctions(const GlRendererOptions& options, const GlFunctions& gl,
                                            std::unique_ptr<GlSplatRenderer>* out) {
  M4D_RETURN_IF_ERROR(CheckOptions(options));
  GlRendererOptions in_context = options;
  in_context.headless = false;
  std::unique_ptr<GlSplatRenderer> created(new GlSplatRenderer(in_context));
  M4D_RETURN_IF_ERROR(created->Initialize(&gl));
  *out = std::move(created);
  return Status::Ok();
}

Status GlSplatRenderer::Initialize(const GlFunctions* loaded) {
  if (loaded) {
    caller_gl_ = *loaded;
    gl_ = &caller_gl_;
    description_ = "caller's context";
  } else if (options_.headless) {
    M4D_RETURN_IF_ERROR(CreateHeadlessGlContext(&context_));
    gl_ = &context_->gl();
    description_ = context_->description();
  } else {
    GlProcLoader loader = options_.loader ? options_.loader : eglGetProcAddress;
    M4D_RETURN_IF_ERROR(LoadGlFunctions(loader, &caller_gl_));
    gl_ = &caller_gl_;
    const auto* renderer = reinterpret_cast<const char*>(gl_->GetString(GL_RENDERER));
    if (renderer == nullptr) {
      return Status(M4D_ERR_UNSUPPORTED, "renderer: no current GL context");
    }
    description_ = std::string("caller's context, ") + renderer;
  }
  return SplatDrawProgram::Create(*gl_, &program_);
}

GlSplatRenderer::~GlSplatRenderer() {
  if (context_) context_->MakeCurrent();
  program_.reset();
  framebuffer_.reset();
}

Status GlSplatRenderer::Upload(const M4dGaussians* layers, int layer_count) {
  size_t total = 0;
  for (int l = 0; l < layer_count; ++l) {
    M4D_RETURN_IF_ERROR(CheckLayer(layers[l]));
    total += layers[l].count;
  }
  if (total > options_.max_gaussians) {
    return Status(M4D_ERR_LIMIT, "renderer: " + std::to_string(total) +
                                     " Gaussians exceed the limit of " +
                                     std::to_string(options_.max_gaussians));
  }
  layers_.resize(static_cast<size_t>(layer_count));
  for (int l = 0; l < layer_count; ++l) CopyLayer(layers[l], &layers_[l]);
  return Status::Ok();
}

Status GlSplatRenderer::HeadlessTarget(int width, int height) {
  if (framebuffer_ && framebuffer_->width() == width && framebuffer_->height() == height) {
    return Status::Ok();
  }
  framebuffer_.reset();
  return OffscreenFramebuffer::Create(*gl_, width, height, 0, ColorFormat::kRgba8, &framebuffer_);
}

Status GlSplatRenderer::Draw(const Camera& camera) {
  if (context_) M4D_RETURN_IF_ERROR(context_->MakeCurrent());
  std::vector<M4dGaussians> views;
  for (const GaussianSet& set : layers_) views.push_back(GaussianView(set));
  SplatInstanceTimings cpu;
  M4D_RETURN_IF_ERROR(instances_builder_.Build(camera, views.data(), static_cast<int>(views.size()),
                                               options_.sh_degree, &instances_, &cpu));
  timings_.visible = instances_.size();
  timings_.project_ms = cpu.project_ms;
  timings_.sort_ms = cpu.sort_ms;

  Clock::time_point start = Clock::now();
  int viewport[4] = {0, 0, camera.width, camera.height};
  if (context_) {
    M4D_RETURN_IF_ERROR(HeadlessTarget(camera.width, camera.height));
    framebuffer_->Bind();
  } else {
    gl_->GetIntegerv(GL_VIEWPORT, viewport);
  }
  program_->Upload(instances_.data(), instances_.size());
  timings_.upload_ms = MillisecondsSince(start);

  start = Clock::now();
  gl_->Enable(GL_SCISSOR_TEST);
  gl_->Scissor(viewport[0], viewport[1], viewport[2], viewport[3]);
  program_->Draw(viewport, options_.background, true);
  gl_->Disable(GL_SCISSOR_TEST);
  gl_->Finish();
  timings_.draw_ms = MillisecondsSince(start);
  const GLenum error = gl_->GetError();
  if (error != GL_NO_ERROR) {
    return Status(M4D_ERR_UNSUPPORTED, "renderer: GL error " + std::to_string(error));
  }
  drawn_ = context_ != nullptr;
  return Status::Ok();
}

Status GlSplatRenderer::ReadRgb(uint8_t* rgb, size_t size) {
  if (!drawn_) return Status(M4D_ERR_INVALID_ARG, "renderer: no headless draw to read");
  const size_t pixels = static_cast<size_t>(framebuffer_->width()) * framebuffer_->height();
  if (rgb == nullptr || size < 3 * pixels) {
    return Status(M4D_ERR_INVALID_ARG,
                  "renderer: the RGB buffer needs " + std::to_string(3 * pixels) + " bytes");
  }
  M4D_RETURN_IF_ERROR(context_->MakeCurrent());
  M4D_RETURN_IF_ERROR(framebuffer_->ReadRgba8(&rgba_));
  for (size_t p = 0; p < pixels; ++p) std::memcpy(rgb + 3 * p, &rgba_[4 * p], 3);
  return Status::Ok();
}

}  // namespace m4d
