#include "sdk/src/gl/splat_draw_program.h"

#include <string>

#include "sdk/src/gl/shader_program.h"

namespace m4d {
namespace {

// u_viewport: x, y, width, height of the image in window coordinates; image pixel (u, v), v
// down, maps to window (x + u, y + height - v). The quad's corners are (+-1, +-1) in units of
// the ellipse's half axes at k. v_q: the fragment's offset in standard deviations along the
// axes scaled by sqrt(0.5 log2 e), so that 2^-|v_q|^2 = exp(-0.5 d^T conic d), the reference's
// alpha falloff (exp2 is the cheaper one on llvmpipe); v_d: its offset in pixels, for the
// reference's visited box.
constexpr char kSplatVertexShader[] = R"(#version 300 es
precision highp float;
layout(location = 0) in vec4 a_mean_axis;
layout(location = 1) in vec4 a_minor_k_extent;
layout(location = 2) in vec4 a_color_opacity;
uniform vec4 u_viewport;
out vec2 v_q;
out vec2 v_d;
flat out vec2 v_extent;
flat out vec4 v_color_opacity;
void main() {
  vec2 corner = vec2(float(gl_VertexID & 1), float(gl_VertexID >> 1)) * 2.0 - 1.0;
  vec2 major = a_mean_axis.zw;
  float major_length = length(major);
  vec2 minor = major_length > 0.0 ? vec2(-major.y, major.x) * (a_minor_k_extent.x / major_length)
                                  : vec2(0.0);
  vec2 offset = corner.x * major + corner.y * minor;
  vec2 pixel = a_mean_axis.xy + offset;
  gl_Position = vec4(2.0 * pixel.x / u_viewport.z - 1.0, 1.0 - 2.0 * pixel.y / u_viewport.w,
                     0.0, 1.0);
  v_q = corner * (a_minor_k_extent.y * 0.84932180);
  v_d = offset;
  v_extent = a_minor_k_extent.zw;
  v_color_opacity = a_color_opacity;
}
)";

constexpr char kSplatFragmentShader[] = R"(#version 300 es
precision highp float;
in vec2 v_q;
in vec2 v_d;
flat in vec2 v_extent;
flat in vec4 v_color_opacity;
out vec4 colour;
void main() {
  if (any(greaterThan(abs(v_d), v_extent))) discard;
  float alpha = min(0.99, v_color_opacity.a * exp2(-dot(v_q, v_q)));
  if (alpha < 1.0 / 255.0) discard;
  colour = vec4(v_color_opacity.rgb * alpha, alpha);
}
)";

constexpr char kBackgroundVertexShader[] = R"(#version 300 es
void main() {
  vec2 corner = vec2(float(gl_VertexID & 1), float(gl_VertexID >> 1)) * 2.0 - 1.0;
  gl_Position = vec4(corner, 0.0, 1.0);
}
)";

constexpr char kBackgroundFragmentShader[] = R"(#version 300 es
precision highp float;
uniform vec3 u_background;
out vec4 colour;
void main() { colour = vec4(u_background, 1.0); }
)";

}  // namespace

Status SplatDrawProgram::Create(const GlFunctions& gl, std::unique_ptr<SplatDrawProgram>* program) {
  std::unique_ptr<SplatDrawProgram> created(new SplatDrawProgram(gl));
  M4D_RETURN_IF_ERROR(created->Initialize());
  *program = std::move(created);
  return Status::Ok();
}

Status SplatDrawProgram::Initialize() {
  M4D_RETURN_IF_ERROR(
      CompileShaderProgram(gl_, kSplatVertexShader, kSplatFragmentShader, &program_));
  M4D_RETURN_IF_ERROR(CompileShaderProgram(gl_, kBackgroundVertexShader, kBackgroundFragmentShader,
                                           &background_program_));
  viewport_location_ = gl_.GetUniformLocation(program_, "u_viewport");
  background_location_ = gl_.GetUniformLocation(background_program_, "u_background");
  gl_.GenBuffers(1, &instance_buffer_);
  gl_.GenVertexArrays(1, &vertex_array_);
  gl_.GenVertexArrays(1, &empty_vertex_array_);
  gl_.BindVertexArray(vertex_array_);
  gl_.BindBuffer(GL_ARRAY_BUFFER, instance_buffer_);
  for (GLuint a = 0; a < 3; ++a) {
    gl_.EnableVertexAttribArray(a);
    gl_.VertexAttribPointer(a, 4, GL_FLOAT, GL_FALSE, sizeof(SplatInstance),
                            reinterpret_cast<const void*>(a * 4 * sizeof(float)));
    gl_.VertexAttribDivisor(a, 1);
  }
  gl_.BindVertexArray(0);
  const GLenum error = gl_.GetError();
  if (error != GL_NO_ERROR) {
    return Status(M4D_ERR_UNSUPPORTED,
                  "gl: creating the splat program failed (GL error " + std::to_string(error) + ")");
  }
  return Status::Ok();
}

SplatDrawProgram::~SplatDrawProgram() {
  gl_.DeleteVertexArrays(1, &vertex_array_);
  gl_.DeleteVertexArrays(1, &empty_vertex_array_);
  gl_.DeleteBuffers(1, &instance_buffer_);
  gl_.DeleteProgram(program_);
  gl_.DeleteProgram(background_program_);
}

void SplatDrawProgram::Upload(const SplatInstance* instances, size_t count) {
  gl_.BindBuffer(GL_ARRAY_BUFFER, instance_buffer_);
  // A new store each frame: the driver need not wait for draws still reading the old one.
  gl_.BufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(count * sizeof(SplatInstance)), instances,
                 GL_STREAM_DRAW);
  count_ = count;
}

void SplatDrawProgram::Draw(const int viewport[4], const float background[3], bool clear) {
  gl_.Disable(GL_DEPTH_TEST);
  gl_.Disable(GL_STENCIL_TEST);
  gl_.Disable(GL_CULL_FACE);
  if (clear) {
    gl_.ClearColor(0.0f, 0.0f, 0.0f, 0.0f);
    gl_.Clear(GL_COLOR_BUFFER_BIT);
  }
  gl_.Enable(GL_BLEND);
  gl_.BlendEquation(GL_FUNC_ADD);
  gl_.BlendFuncSeparate(GL_ONE_MINUS_DST_ALPHA, GL_ONE, GL_ONE_MINUS_DST_ALPHA, GL_ONE);
  gl_.UseProgram(program_);
  gl_.Uniform4f(viewport_location_, static_cast<float>(viewport[0]),
                static_cast<float>(viewport[1]), static_cast<float>(viewport[2]),
                static_cast<float>(viewport[3]));
  gl_.BindVertexArray(vertex_array_);
  if (count_ > 0) gl_.DrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, static_cast<GLsizei>(count_));
  gl_.UseProgram(background_program_);
  gl_.Uniform3fv(background_location_, 1, background);
  gl_.BindVertexArray(empty_vertex_array_);
  gl_.DrawArrays(GL_TRIANGLE_STRIP, 0, 4);
  gl_.BindVertexArray(0);
}

}  // namespace m4d
