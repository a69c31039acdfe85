#include "sdk/src/gl/gl_functions.h"

namespace m4d {

Status LoadGlFunctions(GlProcLoader load, GlFunctions* gl) {
  GlFunctions table;
#define M4D_GL_LOAD(type, name)                                                        \
  table.name = reinterpret_cast<type>(load("gl" #name));                               \
  if (table.name == nullptr) {                                                         \
    *gl = GlFunctions();                                                               \
    return Status(M4D_ERR_UNSUPPORTED, "gl: the context has no entry point gl" #name); \
  }
  M4D_GL_FUNCTION_LIST(M4D_GL_LOAD)
#undef M4D_GL_LOAD
  *gl = table;
  return Status::Ok();
}

}  // namespace m4d
