// The headless GL context (sdk/src/gl): EGL on Mesa's software rasterizer, the function
// table, framebuffer objects with and without multisampling, exact read-back.

#include <gtest/gtest.h>

#include <cstdint>
#include <memory>
#include <vector>

#include "sdk/src/gl/egl_context.h"
#include "sdk/src/gl/gl_functions.h"
#include "sdk/src/gl/offscreen_framebuffer.h"
#include "sdk/src/gl/shader_program.h"

namespace m4d {
namespace {

constexpr int kWidth = 64, kHeight = 48;

// One red triangle over the top-left half of the viewport: corners (-1, 1), (1, 1), (-1, -1)
// in normalised device coordinates, made from gl_VertexID (no buffers needed).
constexpr char kVertexShader[] = R"(#version 300 es
void main() {
  vec2 corners[3] = vec2[3](vec2(-1.0, 1.0), vec2(1.0, 1.0), vec2(-1.0, -1.0));
  gl_Position = vec4(corners[gl_VertexID], 0.0, 1.0);
}
)";
constexpr char kFragmentShader[] = R"(#version 300 es
precision highp float;
out vec4 colour;
void main() { colour = vec4(1.0, 0.0, 0.0, 1.0); }
)";

struct Rgba {
  uint8_t r, g, b, a;
};

Rgba Pixel(const std::vector<uint8_t>& rgba, int x, int y) {
  const uint8_t* p = &rgba[(static_cast<size_t>(y) * kWidth + x) * 4];
  return {p[0], p[1], p[2], p[3]};
}

bool IsRed(Rgba p) { return p.r == 255 && p.g == 0 && p.b == 0 && p.a == 255; }
// The clear colour (0.2, 0.4, 0.6) in bytes: exact, since 0.2 * 255 = 51 and so on.
bool IsClear(Rgba p) { return p.r == 51 && p.g == 102 && p.b == 153 && p.a == 255; }

// Clears to the test colour and draws the triangle into a framebuffer, read back into *rgba.
void DrawTriangle(EglContext* context, int samples, std::vector<uint8_t>* rgba) {
  const GlFunctions& gl = context->gl();
  std::unique_ptr<OffscreenFramebuffer> framebuffer;
  ASSERT_TRUE(OffscreenFramebuffer::Create(gl, kWidth, kHeight, samples, &framebuffer).ok());
  GLuint program = 0;
  const Status compiled = CompileShaderProgram(gl, kVertexShader, kFragmentShader, &program);
  ASSERT_TRUE(compiled.ok()) << compiled.message();
  GLuint vertex_array = 0;
  gl.GenVertexArrays(1, &vertex_array);
  framebuffer->Bind();
  gl.ClearColor(0.2f, 0.4f, 0.6f, 1.0f);
  gl.Clear(GL_COLOR_BUFFER_BIT);
  gl.UseProgram(program);
  gl.BindVertexArray(vertex_array);
  gl.DrawArrays(GL_TRIANGLES, 0, 3);
  const Status read = framebuffer->ReadRgba8(rgba);
  EXPECT_TRUE(read.ok()) << read.message();
  gl.DeleteVertexArrays(1, &vertex_array);
  gl.DeleteProgram(program);
}

TEST(GlContext, CreatesAGles3ContextWithAFullFunctionTable) {
  std::unique_ptr<EglContext> context;
  const Status status = EglContext::Create(&context);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_FALSE(context->description().empty());
  const GlFunctions& gl = context->gl();
#define M4D_EXPECT_LOADED(type, name) EXPECT_NE(gl.name, nullptr) << "gl" #name;
  M4D_GL_FUNCTION_LIST(M4D_EXPECT_LOADED)
#undef M4D_EXPECT_LOADED
  GLint major = 0;
  gl.GetIntegerv(GL_MAJOR_VERSION, &major);
  EXPECT_GE(major, 3);
}

TEST(GlContext, ReadsBackTheClearColourAndATriangleExactly) {
  std::unique_ptr<EglContext> context;
  ASSERT_TRUE(EglContext::Create(&context).ok());
  std::vector<uint8_t> rgba;
  DrawTriangle(context.get(), 1, &rgba);
  ASSERT_EQ(rgba.size(), static_cast<size_t>(kWidth) * kHeight * 4);
  // Row 0 is the top: the triangle covers the top-left half, x_ndc <= y_ndc.
  EXPECT_TRUE(IsRed(Pixel(rgba, 10, 2)));
  EXPECT_TRUE(IsRed(Pixel(rgba, 2, 40)));
  EXPECT_TRUE(IsClear(Pixel(rgba, 40, 44)));
  EXPECT_TRUE(IsClear(Pixel(rgba, 60, 30)));
  int red = 0, clear = 0;
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      red += IsRed(Pixel(rgba, x, y));
      clear += IsClear(Pixel(rgba, x, y));
    }
  }
  // Without multisampling every pixel is one or the other, about half each.
  EXPECT_EQ(red + clear, kWidth * kHeight);
  EXPECT_NEAR(red, kWidth * kHeight / 2, kWidth);
}

TEST(GlContext, MultisampledFramebufferResolvesEdges) {
  std::unique_ptr<EglContext> context;
  ASSERT_TRUE(EglContext::Create(&context).ok());
  std::vector<uint8_t> rgba;
  DrawTriangle(context.get(), 4, &rgba);
  ASSERT_EQ(rgba.size(), static_cast<size_t>(kWidth) * kHeight * 4);
  EXPECT_TRUE(IsRed(Pixel(rgba, 10, 2)));
  EXPECT_TRUE(IsClear(Pixel(rgba, 40, 44)));
  // Pixels the diagonal crosses blend the two colours.
  int blended = 0;
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      const Rgba p = Pixel(rgba, x, y);
      blended += !IsRed(p) && !IsClear(p);
    }
  }
  EXPECT_GT(blended, kHeight / 2);
}

TEST(GlContext, TwoContextsCoexistAndOutliveEachOther) {
  std::unique_ptr<EglContext> first, second;
  ASSERT_TRUE(EglContext::Create(&first).ok());
  ASSERT_TRUE(EglContext::Create(&second).ok());
  first.reset();
  ASSERT_TRUE(second->MakeCurrent().ok());
  std::vector<uint8_t> rgba;
  DrawTriangle(second.get(), 1, &rgba);
  EXPECT_TRUE(IsRed(Pixel(rgba, 10, 2)));
}

TEST(GlContext, FramebufferRejectsBadSizes) {
  std::unique_ptr<EglContext> context;
  ASSERT_TRUE(EglContext::Create(&context).ok());
  std::unique_ptr<OffscreenFramebuffer> framebuffer;
  EXPECT_EQ(OffscreenFramebuffer::Create(context->gl(), 0, 10, 1, &framebuffer).code(),
            M4D_ERR_INVALID_ARG);
  EXPECT_EQ(OffscreenFramebuffer::Create(context->gl(), 10, 1 << 20, 1, &framebuffer).code(),
            M4D_ERR_INVALID_ARG);
  EXPECT_EQ(framebuffer, nullptr);
}

TEST(GlContext, ShaderErrorsCarryTheCompilerLog) {
  std::unique_ptr<EglContext> context;
  ASSERT_TRUE(EglContext::Create(&context).ok());
  GLuint program = 0;
  const Status status = CompileShaderProgram(
      context->gl(), "#version 300 es\nvoid main() { oops; }\n", kFragmentShader, &program);
  EXPECT_EQ(status.code(), M4D_ERR_UNSUPPORTED);
  EXPECT_NE(status.message().find("vertex shader"), std::string::npos);
  EXPECT_EQ(program, 0u);
}

// A loader that knows nothing: the table stays empty and the error names an entry point.
GlProc NoProcs(const char*) { return nullptr; }

TEST(GlContext, LoaderWithoutEntryPointsIsAnError) {
  GlFunctions gl;
  const Status status = LoadGlFunctions(NoProcs, &gl);
  EXPECT_EQ(status.code(), M4D_ERR_UNSUPPORTED);
  EXPECT_NE(status.message().find("glGetError"), std::string::npos);
  EXPECT_EQ(gl.Clear, nullptr);
}

}  // namespace
}  // namespace m4d
