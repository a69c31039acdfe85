#include "encoder/src/synthetic/scene_renderer.h"

#include <glm/gtc/type_ptr.hpp>

#include "sdk/src/gl/shader_program.h"

namespace m4d {
namespace {

constexpr float kNear = 0.05f, kFar = 50.0f;

constexpr char kVertexShader[] = R"(#version 300 es
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec2 a_uv;
uniform mat4 u_model;
uniform mat4 u_view_projection;
out vec3 v_position;
out vec3 v_normal;
out vec2 v_uv;
void main() {
  vec4 world = u_model * vec4(a_position, 1.0);
  v_position = world.xyz;
  v_normal = mat3(u_model) * a_normal;
  v_uv = a_uv;
  gl_Position = u_view_projection * world;
}
)";

// The formula of ShadeSurface (scene_lighting.cc); keep the two in step.
constexpr char kFragmentShader[] = R"(#version 300 es
precision highp float;
uniform sampler2D u_texture;
uniform float u_emissive;
uniform vec3 u_ambient;
uniform vec3 u_sun_direction;
uniform vec3 u_sun_colour;
uniform vec3 u_lamp_position;
uniform vec3 u_lamp_colour;
in vec3 v_position;
in vec3 v_normal;
in vec2 v_uv;
out vec4 o_colour;
void main() {
  vec3 albedo = texture(u_texture, v_uv).rgb;
  vec3 n = normalize(v_normal);
  vec3 to_lamp = u_lamp_position - v_position;
  float d2 = dot(to_lamp, to_lamp);
  float lamp = max(dot(n, to_lamp) / sqrt(d2), 0.0) / (1.0 + d2);
  vec3 light = u_ambient + u_sun_colour * max(dot(n, u_sun_direction), 0.0) + u_lamp_colour * lamp;
  vec3 lit = albedo * ((1.0 - u_emissive) * light + u_emissive * u_lamp_colour);
  o_colour = vec4(clamp(lit, 0.0, 1.0), 1.0);
}
)";

// World to clip space for an OpenCV camera: x_ndc = 2 u / width - 1 and y_ndc = 1 - 2 v /
// height for the pixel position (u, v), depth mapped from [kNear, kFar]. Column-major.
glm::mat4 ViewProjection(const Camera& c) {
  glm::mat4 view(1.0f);
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) view[j][i] = c.rotation[3 * i + j];
    view[3][i] = c.translation[i];
  }
  glm::mat4 projection(0.0f);
  projection[0][0] = 2.0f * c.fx / c.width;
  projection[2][0] = 2.0f * c.cx / c.width - 1.0f;
  projection[1][1] = -2.0f * c.fy / c.height;
  projection[2][1] = 1.0f - 2.0f * c.cy / c.height;
  projection[2][2] = (kFar + kNear) / (kFar - kNear);
  projection[3][2] = -2.0f * kFar * kNear / (kFar - kNear);
  projection[2][3] = 1.0f;
  return projection * view;
}

// Averages factor x factor blocks of RGBA into RGB, rounding to nearest.
void BoxDownsample(const std::vector<uint8_t>& rgba, int width, int height, int factor,
                   std::vector<uint8_t>* rgb) {
  rgb->resize(static_cast<size_t>(width) * height * 3);
  const size_t src_row = static_cast<size_t>(width) * factor * 4;
  const int area = factor * factor;
  for (int y = 0; y < height; ++y) {
    uint8_t* out = rgb->data() + static_cast<size_t>(y) * width * 3;
    for (int x = 0; x < width; ++x) {
      int sum[3] = {0, 0, 0};
      for (int dy = 0; dy < factor; ++dy) {
        const uint8_t* in = rgba.data() + (static_cast<size_t>(y) * factor + dy) * src_row +
                            static_cast<size_t>(x) * factor * 4;
        for (int dx = 0; dx < factor; ++dx) {
          for (int ch = 0; ch < 3; ++ch) sum[ch] += in[4 * dx + ch];
        }
      }
      for (int ch = 0; ch < 3; ++ch)
        out[3 * x + ch] = static_cast<uint8_t>((sum[ch] + area / 2) / area);
    }
  }
}

}  // namespace

Status SceneRenderer::Create(const SceneContent& content, int width, int height, int supersample,
                             int msaa_samples, std::unique_ptr<SceneRenderer>* renderer) {
  std::unique_ptr<SceneRenderer> created(new SceneRenderer(width, height, supersample));
  M4D_RETURN_IF_ERROR(created->Initialize(content, msaa_samples));
  *renderer = std::move(created);
  return Status::Ok();
}

Status SceneRenderer::Initialize(const SceneContent& content, int msaa_samples) {
  M4D_RETURN_IF_ERROR(EglContext::Create(&context_));
  const GlFunctions& gl = context_->gl();
  M4D_RETURN_IF_ERROR(OffscreenFramebuffer::Create(
      gl, width_ * supersample_, height_ * supersample_, msaa_samples, &framebuffer_));
  M4D_RETURN_IF_ERROR(CompileShaderProgram(gl, kVertexShader, kFragmentShader, &program_));
  uniform_model_ = gl.GetUniformLocation(program_, "u_model");
  uniform_view_projection_ = gl.GetUniformLocation(program_, "u_view_projection");
  uniform_emissive_ = gl.GetUniformLocation(program_, "u_emissive");
  uniform_ambient_ = gl.GetUniformLocation(program_, "u_ambient");
  uniform_sun_direction_ = gl.GetUniformLocation(program_, "u_sun_direction");
  uniform_sun_colour_ = gl.GetUniformLocation(program_, "u_sun_colour");
  uniform_lamp_position_ = gl.GetUniformLocation(program_, "u_lamp_position");
  uniform_lamp_colour_ = gl.GetUniformLocation(program_, "u_lamp_colour");
  for (const SceneTexture& texture : content.textures) textures_.push_back(Upload(texture));
  for (const SceneObject& object : content.objects) {
    meshes_.push_back(Upload(object.mesh));
    object_textures_.push_back(object.texture);
    object_emissive_.push_back(object.emissive);
  }
  const GLenum error = gl.GetError();
  if (error != GL_NO_ERROR) {
    return Status(M4D_ERR_UNSUPPORTED, "synthetic scene: uploading to GL failed (GL error " +
                                           std::to_string(error) + ")");
  }
  return Status::Ok();
}

SceneRenderer::GpuMesh SceneRenderer::Upload(const TriangleMesh& mesh) {
  const GlFunctions& gl = context_->gl();
  std::vector<float> vertices;
  vertices.reserve(mesh.vertex_count() * 8);
  for (size_t i = 0; i < mesh.vertex_count(); ++i) {
    const glm::vec3& p = mesh.positions[i];
    const glm::vec3& n = mesh.normals[i];
    const glm::vec2& uv = mesh.uvs[i];
    vertices.insert(vertices.end(), {p.x, p.y, p.z, n.x, n.y, n.z, uv.x, uv.y});
  }
  GpuMesh gpu;
  gpu.index_count = static_cast<GLsizei>(mesh.indices.size());
  gl.GenVertexArrays(1, &gpu.vertex_array);
  gl.BindVertexArray(gpu.vertex_array);
  gl.GenBuffers(2, gpu.buffers);
  gl.BindBuffer(GL_ARRAY_BUFFER, gpu.buffers[0]);
  gl.BufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(vertices.size() * sizeof(float)),
                vertices.data(), GL_STATIC_DRAW);
  gl.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, gpu.buffers[1]);
  gl.BufferData(GL_ELEMENT_ARRAY_BUFFER,
                static_cast<GLsizeiptr>(mesh.indices.size() * sizeof(uint32_t)),
                mesh.indices.data(), GL_STATIC_DRAW);
  const GLsizei stride = 8 * sizeof(float);
  const int sizes[3] = {3, 3, 2}, offsets[3] = {0, 3, 6};
  for (GLuint a = 0; a < 3; ++a) {
    gl.EnableVertexAttribArray(a);
    gl.VertexAttribPointer(a, sizes[a], GL_FLOAT, GL_FALSE, stride,
                           reinterpret_cast<const void*>(offsets[a] * sizeof(float)));
  }
  gl.BindVertexArray(0);
  return gpu;
}

GLuint SceneRenderer::Upload(const SceneTexture& texture) {
  const GlFunctions& gl = context_->gl();
  GLuint id = 0;
  gl.GenTextures(1, &id);
  gl.BindTexture(GL_TEXTURE_2D, id);
  gl.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
  gl.TexImage2D(GL_TEXTURE_2D, 0, GL_RGB8, texture.width, texture.height, 0, GL_RGB,
                GL_UNSIGNED_BYTE, texture.rgb.data());
  gl.GenerateMipmap(GL_TEXTURE_2D);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
  return id;
}

SceneRenderer::~SceneRenderer() {
  if (!context_ || !context_->MakeCurrent().ok()) return;
  const GlFunctions& gl = context_->gl();
  for (const GpuMesh& mesh : meshes_) {
    gl.DeleteVertexArrays(1, &mesh.vertex_array);
    gl.DeleteBuffers(2, mesh.buffers);
  }
  if (!textures_.empty())
    gl.DeleteTextures(static_cast<GLsizei>(textures_.size()), textures_.data());
  if (program_ != 0) gl.DeleteProgram(program_);
  framebuffer_.reset();
}

Status SceneRenderer::Render(const SceneFrameState& state, const Camera& camera,
                             std::vector<uint8_t>* rgb) {
  if (camera.width != width_ || camera.height != height_ || state.model.size() != meshes_.size() ||
      state.visible.size() != meshes_.size()) {
    return Status(M4D_ERR_INVALID_ARG, "synthetic scene: view does not match the renderer");
  }
  const GlFunctions& gl = context_->gl();
  framebuffer_->Bind();
  gl.Enable(GL_DEPTH_TEST);
  gl.DepthFunc(GL_LESS);
  gl.ClearColor(0, 0, 0, 1);
  gl.ClearDepthf(1.0f);
  gl.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  gl.UseProgram(program_);
  const SceneLighting& l = state.lighting;
  gl.UniformMatrix4fv(uniform_view_projection_, 1, GL_FALSE,
                      glm::value_ptr(ViewProjection(camera)));
  gl.Uniform3fv(uniform_ambient_, 1, glm::value_ptr(l.ambient));
  gl.Uniform3fv(uniform_sun_direction_, 1, glm::value_ptr(l.sun_direction));
  gl.Uniform3fv(uniform_sun_colour_, 1, glm::value_ptr(l.sun_colour));
  gl.Uniform3fv(uniform_lamp_position_, 1, glm::value_ptr(l.lamp_position));
  gl.Uniform3fv(uniform_lamp_colour_, 1, glm::value_ptr(l.lamp_colour));
  gl.ActiveTexture(GL_TEXTURE0);
  // Objects come room first; drawing them backwards goes roughly front to back, so the
  // depth test rejects most hidden fragments before they are shaded.
  for (size_t i = meshes_.size(); i-- > 0;) {
    if (!state.visible[i]) continue;
    gl.UniformMatrix4fv(uniform_model_, 1, GL_FALSE, glm::value_ptr(state.model[i]));
    gl.Uniform1f(uniform_emissive_, object_emissive_[i]);
    gl.BindTexture(GL_TEXTURE_2D, textures_[object_textures_[i]]);
    gl.BindVertexArray(meshes_[i].vertex_array);
    gl.DrawElements(GL_TRIANGLES, meshes_[i].index_count, GL_UNSIGNED_INT, nullptr);
  }
  gl.BindVertexArray(0);
  M4D_RETURN_IF_ERROR(framebuffer_->ReadRgba8(&rgba_));
  BoxDownsample(rgba_, width_, height_, supersample_, rgb);
  return Status::Ok();
}

}  // namespace m4d
