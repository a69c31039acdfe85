#include "sdk/src/gl/shader_program.h"

#include <algorithm>
#include <string>
#include <vector>

namespace m4d {
namespace {

std::string ShaderLog(const GlFunctions& gl, GLuint shader) {
  GLint length = 0;
  gl.GetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
  std::vector<char> log(static_cast<size_t>(std::max(length, 1)), '\0');
  gl.GetShaderInfoLog(shader, static_cast<GLsizei>(log.size()), nullptr, log.data());
  return log.data();
}

std::string ProgramLog(const GlFunctions& gl, GLuint program) {
  GLint length = 0;
  gl.GetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
  std::vector<char> log(static_cast<size_t>(std::max(length, 1)), '\0');
  gl.GetProgramInfoLog(program, static_cast<GLsizei>(log.size()), nullptr, log.data());
  return log.data();
}

Status CompileShader(const GlFunctions& gl, GLenum stage, const char* source, GLuint* shader) {
  *shader = gl.CreateShader(stage);
  gl.ShaderSource(*shader, 1, &source, nullptr);
  gl.CompileShader(*shader);
  GLint compiled = GL_FALSE;
  gl.GetShaderiv(*shader, GL_COMPILE_STATUS, &compiled);
  if (compiled == GL_TRUE) return Status::Ok();
  const std::string log = ShaderLog(gl, *shader);
  gl.DeleteShader(*shader);
  *shader = 0;
  return Status(M4D_ERR_UNSUPPORTED, std::string("gl: ") +
                                         (stage == GL_VERTEX_SHADER ? "vertex" : "fragment") +
                                         " shader does not compile: " + log);
}

}  // namespace

Status CompileShaderProgram(const GlFunctions& gl, const char* vertex_source,
                            const char* fragment_source, GLuint* program) {
  GLuint vertex = 0, fragment = 0;
  M4D_RETURN_IF_ERROR(CompileShader(gl, GL_VERTEX_SHADER, vertex_source, &vertex));
  Status status = CompileShader(gl, GL_FRAGMENT_SHADER, fragment_source, &fragment);
  if (!status.ok()) {
    gl.DeleteShader(vertex);
    return status;
  }
  *program = gl.CreateProgram();
  gl.AttachShader(*program, vertex);
  gl.AttachShader(*program, fragment);
  gl.LinkProgram(*program);
  // The program keeps the attached shaders alive; deleting them now frees them with it.
  gl.DeleteShader(vertex);
  gl.DeleteShader(fragment);
  GLint linked = GL_FALSE;
  gl.GetProgramiv(*program, GL_LINK_STATUS, &linked);
  if (linked == GL_TRUE) return Status::Ok();
  const std::string log = ProgramLog(gl, *program);
  gl.DeleteProgram(*program);
  *program = 0;
  return Status(M4D_ERR_UNSUPPORTED, "gl: shader program does not link: " + log);
}

}  // namespace m4d
