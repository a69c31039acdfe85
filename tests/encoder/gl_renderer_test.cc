// The OpenGL ES renderer (m4d_render.h) against the CPU reference rasterizer: frames of a
// decoded conformance stream (SH degree 3, several GOPs) from several cameras agree at 40 dB
// or better, headless on Mesa (EGL surfaceless, and the OSMesa fallback); foreground-only
// uploads draw only the dynamic layer; bad arguments fail cleanly.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <memory>
#include <string>
#include <vector>

#include "encoder/src/raster/render_context.h"
#include "encoder/src/raster/splat_renderer.h"
#include "encoder/src/synthetic/synthetic_content.h"
#include "m4d/m4d.h"
#include "m4d/m4d_render.h"
#include "sdk/src/gl/egl_context.h"
#include "sdk/src/gl/gl_splat_renderer.h"
#include "sdk/src/gl/osmesa_context.h"
#include "tests/encoder/stream_test_util.h"
#include "tests/raster/splat_test_scenes.h"

namespace m4d {
namespace {

constexpr int kWidth = 160, kHeight = 120;
const float kBackground[3] = {0.1f, 0.2f, 0.3f};

std::vector<testing::Packet> ConformancePackets(const std::string& name) {
  std::ifstream file(std::string(M4D_SOURCE_DIR) + "/conformance/streams/" + name,
                     std::ios::binary);
  std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(file)),
                             std::istreambuf_iterator<char>());
  return testing::SplitPackets(bytes);
}

// Decodes every frame; each is kept (the caller unrefs).
std::vector<M4dFrame> DecodeFrames(const std::vector<testing::Packet>& packets) {
  M4dSettings settings = testing::DefaultSettings();
  M4dContext* ctx = nullptr;
  EXPECT_EQ(m4d_open(&ctx, &settings), M4D_OK);
  std::vector<M4dFrame> frames;
  auto drain = [&]() {
    M4dFrame frame;
    while (m4d_get_frame(ctx, &frame) == M4D_OK) frames.push_back(frame);
  };
  for (const testing::Packet& p : packets) {
    if (m4d_send_packet(ctx, p.data(), p.size()) == M4D_ERR_AGAIN) {
      drain();
      EXPECT_EQ(m4d_send_packet(ctx, p.data(), p.size()), M4D_OK);
    }
    drain();
  }
  m4d_close(&ctx);
  return frames;
}

// Cameras on a ring around the origin, looking at it.
std::vector<Camera> RingCameras() {
  std::vector<Camera> cameras;
  const float target[3] = {0, 0, 0};
  for (int c = 0; c < 3; ++c) {
    const float angle = 2.1f * static_cast<float>(c);
    const float eye[3] = {5.0f * std::sin(angle), 0.8f - 0.7f * c, -5.0f * std::cos(angle)};
    cameras.push_back(test::LookAtCamera(kWidth, kHeight, 150.0f, 3.0f * c, -2.0f, eye, target));
  }
  return cameras;
}

M4dRenderCamera ToApiCamera(const Camera& c) {
  M4dRenderCamera out = {};
  out.width = static_cast<uint32_t>(c.width);
  out.height = static_cast<uint32_t>(c.height);
  out.fx = c.fx;
  out.fy = c.fy;
  out.cx = c.cx;
  out.cy = c.cy;
  std::copy(c.rotation, c.rotation + 9, out.rotation);
  std::copy(c.translation, c.translation + 3, out.translation);
  out.near_plane = c.near_plane;
  return out;
}

// The CPU reference render of the frame's selected layers, as RGB bytes.
std::vector<uint8_t> ReferenceRgb(const M4dFrame& frame, uint32_t layers, const Camera& camera) {
  std::vector<M4dGaussians> views;
  if ((layers & M4D_LAYER_STATIC) && frame.static_layer.count) {
    views.push_back(frame.static_layer);
  }
  if ((layers & M4D_LAYER_DYNAMIC) && frame.dynamic_layer.count) {
    views.push_back(frame.dynamic_layer);
  }
  RenderSettings settings;
  settings.threads = 2;
  std::copy(kBackground, kBackground + 3, settings.background);
  RenderContext context;
  EXPECT_TRUE(RenderForward(camera, views.data(), static_cast<int>(views.size()), settings, nullptr,
                            &context)
                  .ok());
  std::vector<uint8_t> rgb(context.color.size());
  for (size_t i = 0; i < rgb.size(); ++i) {
    rgb[i] = static_cast<uint8_t>(std::clamp(context.color[i], 0.0f, 1.0f) * 255.0f + 0.5f);
  }
  return rgb;
}

double Psnr(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
  double sum = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    const double d = static_cast<double>(a[i]) - b[i];
    sum += d * d;
  }
  const double mse = sum / static_cast<double>(a.size());
  return mse == 0 ? 99.0 : 10.0 * std::log10(255.0 * 255.0 / mse);
}

// Pixels that differ from the background: the render is not empty.
size_t Covered(const std::vector<uint8_t>& rgb) {
  size_t n = 0;
  for (size_t p = 0; p < rgb.size() / 3; ++p) {
    n += std::abs(rgb[3 * p] - std::lround(kBackground[0] * 255)) > 8;
  }
  return n;
}

class GlRendererTest : public ::testing::Test {
 protected:
  void SetUp() override {
    frames_ = DecodeFrames(ConformancePackets("synth_sh3_three_gops.m4d"));
    ASSERT_GE(frames_.size(), 6u);
    M4dRendererSettings s;
    m4d_renderer_default_settings(&s);
    std::copy(kBackground, kBackground + 3, s.background);
    s.threads = 2;
    ASSERT_EQ(m4d_renderer_open(&renderer_, &s), M4D_OK);
  }
  void TearDown() override {
    m4d_renderer_close(&renderer_);
    for (M4dFrame& f : frames_) m4d_frame_unref(&f);
  }

  std::vector<uint8_t> Draw(const M4dFrame& frame, uint32_t layers, const Camera& camera) {
    EXPECT_EQ(m4d_renderer_upload(renderer_, &frame, layers), M4D_OK);
    const M4dRenderCamera api = ToApiCamera(camera);
    EXPECT_EQ(m4d_renderer_draw(renderer_, &api), M4D_OK) << m4d_renderer_last_error(renderer_);
    std::vector<uint8_t> rgb(3 * kWidth * kHeight);
    EXPECT_EQ(m4d_renderer_read_rgb(renderer_, rgb.data(), rgb.size()), M4D_OK);
    return rgb;
  }

  std::vector<M4dFrame> frames_;
  M4dRenderer* renderer_ = nullptr;
};

TEST_F(GlRendererTest, AgreesWithTheCpuReference) {
  const std::vector<Camera> cameras = RingCameras();
  for (size_t f : {size_t{0}, size_t{2}, frames_.size() - 1}) {
    for (size_t c = 0; c < cameras.size(); ++c) {
      const std::vector<uint8_t> gl = Draw(frames_[f], M4D_LAYER_ALL, cameras[c]);
      const std::vector<uint8_t> cpu = ReferenceRgb(frames_[f], M4D_LAYER_ALL, cameras[c]);
      EXPECT_GT(Covered(cpu), static_cast<size_t>(kWidth * kHeight / 10)) << f << " " << c;
      EXPECT_GE(Psnr(gl, cpu), 40.0) << "frame " << f << " camera " << c;
    }
  }
  M4dRenderStats stats;
  ASSERT_EQ(m4d_renderer_stats(renderer_, &stats), M4D_OK);
  EXPECT_GT(stats.visible, 0u);
}

TEST_F(GlRendererTest, ForegroundOnlyDrawsTheDynamicLayer) {
  const Camera camera = RingCameras()[0];
  const std::vector<uint8_t> gl = Draw(frames_[1], M4D_LAYER_DYNAMIC, camera);
  const std::vector<uint8_t> cpu = ReferenceRgb(frames_[1], M4D_LAYER_DYNAMIC, camera);
  const std::vector<uint8_t> all = ReferenceRgb(frames_[1], M4D_LAYER_ALL, camera);
  EXPECT_GE(Psnr(gl, cpu), 40.0);
  EXPECT_LT(Psnr(gl, all), 30.0);  // the background layer is really missing
  EXPECT_LT(Covered(gl), Covered(all));
}

TEST_F(GlRendererTest, RejectsBadArguments) {
  Camera camera = RingCameras()[0];
  std::vector<uint8_t> rgb(3 * kWidth * kHeight);
  EXPECT_EQ(m4d_renderer_read_rgb(renderer_, rgb.data(), rgb.size()), M4D_ERR_INVALID_ARG);
  EXPECT_EQ(m4d_renderer_upload(renderer_, nullptr, M4D_LAYER_ALL), M4D_ERR_INVALID_ARG);
  EXPECT_EQ(m4d_renderer_upload(renderer_, &frames_[0], 8u), M4D_ERR_INVALID_ARG);
  M4dRenderCamera api = ToApiCamera(camera);
  api.fx = -1.0f;
  EXPECT_EQ(m4d_renderer_draw(renderer_, &api), M4D_ERR_INVALID_ARG);
  EXPECT_STRNE(m4d_renderer_last_error(renderer_), "");
  api = ToApiCamera(camera);
  api.width = 0;
  EXPECT_EQ(m4d_renderer_draw(renderer_, &api), M4D_ERR_INVALID_ARG);
  api = ToApiCamera(camera);
  api.reserved[15] = 1;  // refused as the settings' reserved bytes are
  EXPECT_EQ(m4d_renderer_draw(renderer_, &api), M4D_ERR_INVALID_ARG);
  EXPECT_EQ(m4d_renderer_draw(renderer_, nullptr), M4D_ERR_INVALID_ARG);
  Draw(frames_[0], M4D_LAYER_ALL, camera);
  EXPECT_EQ(m4d_renderer_read_rgb(renderer_, rgb.data(), rgb.size() - 1), M4D_ERR_INVALID_ARG);

  M4dRendererSettings s;
  m4d_renderer_default_settings(&s);
  M4dRenderer* r = reinterpret_cast<M4dRenderer*>(&s);
  s.reserved[3] = 1;
  EXPECT_EQ(m4d_renderer_open(&r, &s), M4D_ERR_INVALID_ARG);
  EXPECT_EQ(r, nullptr);
  m4d_renderer_default_settings(&s);
  s.sh_degree = 4;
  EXPECT_EQ(m4d_renderer_open(&r, &s), M4D_ERR_INVALID_ARG);
  EXPECT_EQ(m4d_renderer_open(nullptr, &s), M4D_ERR_INVALID_ARG);
  m4d_renderer_close(nullptr);
  EXPECT_NE(std::string(m4d_renderer_description(renderer_)), "");
}

// In the caller's context (its own EGL context and framebuffer here): the same image as
// headless, through the public API.
TEST_F(GlRendererTest, DrawsInTheCallersContext) {
  const Camera camera = RingCameras()[2];
  const std::vector<uint8_t> headless = Draw(frames_[4], M4D_LAYER_ALL, camera);
  std::unique_ptr<EglContext> context;
  ASSERT_TRUE(EglContext::Create(&context).ok());
  std::unique_ptr<OffscreenFramebuffer> target;
  ASSERT_TRUE(OffscreenFramebuffer::Create(context->gl(), kWidth, kHeight, 0, &target).ok());
  target->Bind();
  M4dRendererSettings s;
  m4d_renderer_default_settings(&s);
  s.context = M4D_RENDER_CURRENT_CONTEXT;
  s.threads = 2;
  std::copy(kBackground, kBackground + 3, s.background);
  M4dRenderer* in_context = nullptr;
  ASSERT_EQ(m4d_renderer_open(&in_context, &s), M4D_OK);
  ASSERT_EQ(m4d_renderer_upload(in_context, &frames_[4], M4D_LAYER_ALL), M4D_OK);
  const M4dRenderCamera api = ToApiCamera(camera);
  ASSERT_EQ(m4d_renderer_draw(in_context, &api), M4D_OK) << m4d_renderer_last_error(in_context);
  std::vector<uint8_t> unused(3 * kWidth * kHeight);
  EXPECT_EQ(m4d_renderer_read_rgb(in_context, unused.data(), unused.size()), M4D_ERR_INVALID_ARG);
  std::vector<uint8_t> rgba;
  ASSERT_TRUE(target->ReadRgba8(&rgba).ok());
  std::vector<uint8_t> rgb(3 * kWidth * kHeight);
  for (size_t p = 0; p < rgb.size() / 3; ++p) std::copy_n(&rgba[4 * p], 3, &rgb[3 * p]);
  EXPECT_GE(Psnr(rgb, headless), 60.0);
  m4d_renderer_close(&in_context);
  target.reset();
}

// Dense content (a ball covered about ten times over, as trained surfaces are) accumulates
// many 8-bit blends per pixel; they still agree.
TEST_F(GlRendererTest, DenseContentAgrees) {
  const float centre[3] = {0, 0, 0};
  GaussianSet ball = SyntheticGaussianSet(8000, 3, 11, centre, 1.2f);
  const float spacing = std::sqrt(4.0f * 3.14159265f * 1.44f / 8000.0f);
  for (size_t i = 0; i < ball.size(); ++i) {
    for (int a = 0; a < 3; ++a) {
      ball.log_scales[3 * i + a] = std::log(0.7f * spacing) + 0.3f * std::sin(float(5 * i + a));
    }
  }
  std::unique_ptr<GlSplatRenderer> renderer;
  GlRendererOptions options;
  options.threads = 2;
  std::copy(kBackground, kBackground + 3, options.background);
  ASSERT_TRUE(GlSplatRenderer::Create(options, &renderer).ok());
  const M4dGaussians layer = GaussianView(ball);
  ASSERT_TRUE(renderer->Upload(&layer, 1).ok());
  for (const Camera& camera : RingCameras()) {
    ASSERT_TRUE(renderer->Draw(camera).ok());
    std::vector<uint8_t> gl(3 * kWidth * kHeight);
    ASSERT_TRUE(renderer->ReadRgb(gl.data(), gl.size()).ok());
    RenderSettings settings;
    settings.threads = 2;
    std::copy(kBackground, kBackground + 3, settings.background);
    RenderContext context;
    ASSERT_TRUE(RenderForward(camera, &layer, 1, settings, nullptr, &context).ok());
    std::vector<uint8_t> cpu(gl.size());
    for (size_t i = 0; i < cpu.size(); ++i) {
      cpu[i] = static_cast<uint8_t>(std::clamp(context.color[i], 0.0f, 1.0f) * 255.0f + 0.5f);
    }
    EXPECT_GT(Covered(cpu), static_cast<size_t>(kWidth * kHeight / 10));
    EXPECT_GE(Psnr(gl, cpu), 40.0);
  }
}

// The fallback context renders the same image through the same code.
TEST_F(GlRendererTest, OsmesaFallbackAgrees) {
  const Camera camera = RingCameras()[1];
  const std::vector<uint8_t> egl = Draw(frames_[3], M4D_LAYER_ALL, camera);
  // Made after the EGL draw: both libraries share Mesa's dispatch, and EGL does not rebind a
  // context it believes current.
  std::unique_ptr<OsmesaContext> osmesa;
  const Status made = OsmesaContext::Create(&osmesa);
  ASSERT_TRUE(made.ok()) << made.message();
  EXPECT_NE(osmesa->description().find("OSMesa"), std::string::npos);

  ASSERT_TRUE(osmesa->MakeCurrent().ok());
  GlRendererOptions options;
  options.headless = false;  // in OSMesa's current context, into a framebuffer of ours
  options.threads = 2;
  std::copy(kBackground, kBackground + 3, options.background);
  std::unique_ptr<OffscreenFramebuffer> target;
  ASSERT_TRUE(
      OffscreenFramebuffer::Create(osmesa->gl(), kWidth, kHeight, 0, ColorFormat::kRgba16f, &target)
          .ok());
  target->Bind();
  // The loader of OSMesa's context is the one its table was filled with; reuse the table.
  std::unique_ptr<GlSplatRenderer> renderer;
  ASSERT_TRUE(GlSplatRenderer::CreateWithFunctions(options, osmesa->gl(), &renderer).ok());
  const M4dGaussians layers[2] = {frames_[3].static_layer, frames_[3].dynamic_layer};
  ASSERT_TRUE(renderer->Upload(layers, 2).ok());
  const Status drawn = renderer->Draw(camera);
  ASSERT_TRUE(drawn.ok()) << drawn.message();
  std::vector<uint8_t> rgba;
  ASSERT_TRUE(target->ReadRgba8(&rgba).ok());
  std::vector<uint8_t> rgb(3 * kWidth * kHeight);
  for (size_t p = 0; p < rgb.size() / 3; ++p) std::copy_n(&rgba[4 * p], 3, &rgb[3 * p]);
  EXPECT_GE(Psnr(rgb, egl), 45.0);
  renderer.reset();
  target.reset();
  osmesa->ReleaseCurrent();
}

}  // namespace
}  // namespace m4d
