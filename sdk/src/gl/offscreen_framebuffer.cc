#include "sdk/src/gl/offscreen_framebuffer.h"

#include <algorithm>
#include <string>

namespace m4d {

Status OffscreenFramebuffer::Create(const GlFunctions& gl, int width, int height, int samples,
                                    std::unique_ptr<OffscreenFramebuffer>* framebuffer) {
  return Create(gl, width, height, samples, ColorFormat::kRgba8, framebuffer);
}

Status OffscreenFramebuffer::Create(const GlFunctions& gl, int width, int height, int samples,
                                    ColorFormat format,
                                    std::unique_ptr<OffscreenFramebuffer>* framebuffer) {
  std::unique_ptr<OffscreenFramebuffer> created(new OffscreenFramebuffer(gl, format));
  M4D_RETURN_IF_ERROR(created->Initialize(width, height, samples));
  *framebuffer = std::move(created);
  return Status::Ok();
}

Status OffscreenFramebuffer::Initialize(int width, int height, int samples) {
  GLint max_size = 0, max_samples = 0;
  gl_.GetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &max_size);
  gl_.GetIntegerv(GL_MAX_SAMPLES, &max_samples);
  if (width < 1 || height < 1 || width > max_size || height > max_size) {
    return Status(M4D_ERR_INVALID_ARG, "gl: framebuffer size " + std::to_string(width) + "x" +
                                           std::to_string(height) + " outside 1.." +
                                           std::to_string(max_size));
  }
  width_ = width;
  height_ = height;
  samples_ = samples > 1 ? std::min(samples, static_cast<int>(max_samples)) : 0;
  M4D_RETURN_IF_ERROR(CreateTarget(samples_, &draw_framebuffer_, draw_renderbuffers_));
  if (samples_ > 1) {
    M4D_RETURN_IF_ERROR(CreateTarget(0, &resolve_framebuffer_, resolve_renderbuffers_));
  }
  return Status::Ok();
}

Status OffscreenFramebuffer::CreateTarget(int samples, GLuint* framebuffer,
                                          GLuint renderbuffers[2]) {
  gl_.GenFramebuffers(1, framebuffer);
  gl_.BindFramebuffer(GL_FRAMEBUFFER, *framebuffer);
  gl_.GenRenderbuffers(2, renderbuffers);
  const GLenum color = format_ == ColorFormat::kRgba16f ? GL_RGBA16F : GL_RGBA8;
  const GLenum formats[2] = {color, GL_DEPTH_COMPONENT24};
  const GLenum attachments[2] = {GL_COLOR_ATTACHMENT0, GL_DEPTH_ATTACHMENT};
  for (int i = 0; i < 2; ++i) {
    gl_.BindRenderbuffer(GL_RENDERBUFFER, renderbuffers[i]);
    gl_.RenderbufferStorageMultisample(GL_RENDERBUFFER, samples, formats[i], width_, height_);
    gl_.FramebufferRenderbuffer(GL_FRAMEBUFFER, attachments[i], GL_RENDERBUFFER, renderbuffers[i]);
  }
  const GLenum status = gl_.CheckFramebufferStatus(GL_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    return Status(M4D_ERR_UNSUPPORTED, "gl: framebuffer incomplete (status " +
                                           std::to_string(status) + ", " + std::to_string(width_) +
                                           "x" + std::to_string(height_) + ", " +
                                           std::to_string(samples) + " samples)");
  }
  return Status::Ok();
}

OffscreenFramebuffer::~OffscreenFramebuffer() {
  gl_.BindFramebuffer(GL_FRAMEBUFFER, 0);
  gl_.DeleteFramebuffers(1, &draw_framebuffer_);
  gl_.DeleteRenderbuffers(2, draw_renderbuffers_);
  gl_.DeleteFramebuffers(1, &resolve_framebuffer_);
  gl_.DeleteRenderbuffers(2, resolve_renderbuffers_);
}

void OffscreenFramebuffer::Bind() {
  gl_.BindFramebuffer(GL_FRAMEBUFFER, draw_framebuffer_);
  gl_.Viewport(0, 0, width_, height_);
}

Status OffscreenFramebuffer::ReadRgba8(std::vector<uint8_t>* rgba) {
  const size_t values = static_cast<size_t>(width_) * height_ * 4;
  if (format_ == ColorFormat::kRgba8) {
    rgba->resize(values);
    return ReadPixels(rgba->data());
  }
  std::vector<float> pixels(values);
  M4D_RETURN_IF_ERROR(ReadPixels(pixels.data()));
  rgba->resize(values);
  for (size_t i = 0; i < values; ++i) {
    (*rgba)[i] = static_cast<uint8_t>(std::clamp(pixels[i], 0.0f, 1.0f) * 255.0f + 0.5f);
  }
  return Status::Ok();
}

// Reads width * height RGBA values (bytes or floats, as the colour format) into pixels.
Status OffscreenFramebuffer::ReadPixels(void* pixels) {
  GLuint read_from = draw_framebuffer_;
  if (samples_ > 1) {
    gl_.BindFramebuffer(GL_READ_FRAMEBUFFER, draw_framebuffer_);
    gl_.BindFramebuffer(GL_DRAW_FRAMEBUFFER, resolve_framebuffer_);
    gl_.BlitFramebuffer(0, 0, width_, height_, 0, 0, width_, height_, GL_COLOR_BUFFER_BIT,
                        GL_NEAREST);
    read_from = resolve_framebuffer_;
  }
  gl_.BindFramebuffer(GL_FRAMEBUFFER, read_from);
  const bool bytes = format_ == ColorFormat::kRgba8;
  const size_t row_bytes = static_cast<size_t>(width_) * 4 * (bytes ? 1 : sizeof(float));
  gl_.PixelStorei(GL_PACK_ALIGNMENT, 1);
  gl_.ReadPixels(0, 0, width_, height_, GL_RGBA, bytes ? GL_UNSIGNED_BYTE : GL_FLOAT, pixels);
  gl_.BindFramebuffer(GL_FRAMEBUFFER, draw_framebuffer_);
  const GLenum error = gl_.GetError();
  if (error != GL_NO_ERROR) {
    return Status(M4D_ERR_UNSUPPORTED,
                  "gl: reading the framebuffer failed (GL error " + std::to_string(error) + ")");
  }
  // GL's row 0 is the bottom one.
  auto* data = static_cast<uint8_t*>(pixels);
  for (int top = 0, bottom = height_ - 1; top < bottom; ++top, --bottom) {
    std::swap_ranges(data + top * row_bytes, data + (top + 1) * row_bytes,
                     data + bottom * row_bytes);
  }
  return Status::Ok();
}

}  // namespace m4d
