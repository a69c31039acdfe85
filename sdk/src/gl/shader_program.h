// Compiling and linking a GLSL ES vertex + fragment shader pair into a program object, with
// the compiler's log in the error.
#ifndef M4D_SDK_GL_SHADER_PROGRAM_H_
#define M4D_SDK_GL_SHADER_PROGRAM_H_

#include "sdk/src/common/status.h"
#include "sdk/src/gl/gl_functions.h"

namespace m4d {

// On success *program is a linked program owned by the caller (gl.DeleteProgram). On
// failure M4D_ERR_UNSUPPORTED with the stage and the info log; nothing is left allocated.
Status CompileShaderProgram(const GlFunctions& gl, const char* vertex_source,
                            const char* fragment_source, GLuint* program);

}  // namespace m4d

#endif  // M4D_SDK_GL_SHADER_PROGRAM_H_
