#include "sdk/src/gl/osmesa_context.h"

#include <dlfcn.h>

#include <cstring>

namespace m4d {
namespace {

// From Mesa's GL/osmesa.h (not included: it pulls in desktop GL's header, which clashes with
// GLES3/gl3.h).
constexpr int kOsmesaFormat = 0x22;
constexpr int kOsmesaRgba = 0x1908;  // GL_RGBA
constexpr int kOsmesaDepthBits = 0x30;
constexpr int kOsmesaProfile = 0x33;
constexpr int kOsmesaCoreProfile = 0x34;
constexpr int kOsmesaMajorVersion = 0x36;
constexpr int kOsmesaMinorVersion = 0x37;
constexpr unsigned kGlUnsignedByte = 0x1401;

using CreateContextAttribs = void* (*)(const int* attributes, void* share);
using DestroyContext = void (*)(void* context);
using MakeCurrentFn = unsigned char (*)(void* context, void* buffer, unsigned type, int width,
                                        int height);
template <typename T>
T Symbol(void* library, const char* name) {
  return reinterpret_cast<T>(dlsym(library, name));
}

}  // namespace

Status OsmesaContext::Create(std::unique_ptr<OsmesaContext>* context) {
  std::unique_ptr<OsmesaContext> created(new OsmesaContext());
  M4D_RETURN_IF_ERROR(created->Initialize());
  *context = std::move(created);
  return Status::Ok();
}

Status OsmesaContext::Initialize() {
  // RTLD_NODELETE: Mesa keeps process-wide driver state that it never frees; unmapping it at
  // dlclose would leave that state dangling, and a second context would load it afresh.
  for (const char* name : {"libOSMesa.so.8", "libOSMesa.so.6", "libOSMesa.so"}) {
    library_ = dlopen(name, RTLD_NOW | RTLD_LOCAL | RTLD_NODELETE);
    if (library_ != nullptr) break;
  }
  if (library_ == nullptr) return Status(M4D_ERR_UNSUPPORTED, "gl: libOSMesa not found");
  const auto create = Symbol<CreateContextAttribs>(library_, "OSMesaCreateContextAttribs");
  const auto get_proc = Symbol<GlProcLoader>(library_, "OSMesaGetProcAddress");
  if (create == nullptr || get_proc == nullptr ||
      !Symbol<MakeCurrentFn>(library_, "OSMesaMakeCurrent") ||
      !Symbol<DestroyContext>(library_, "OSMesaDestroyContext")) {
    return Status(M4D_ERR_UNSUPPORTED, "gl: libOSMesa lacks OSMesaCreateContextAttribs");
  }
  const int attributes[] = {kOsmesaFormat,
                            kOsmesaRgba,
                            kOsmesaDepthBits,
                            24,
                            kOsmesaProfile,
                            kOsmesaCoreProfile,
                            kOsmesaMajorVersion,
                            3,
                            kOsmesaMinorVersion,
                            3,
                            0};
  context_ = create(attributes, nullptr);
  if (context_ == nullptr) {
    return Status(M4D_ERR_UNSUPPORTED, "gl: OSMesa has no OpenGL 3.3 core context");
  }
  M4D_RETURN_IF_ERROR(MakeCurrent());
  M4D_RETURN_IF_ERROR(LoadGlFunctions(get_proc, &gl_));
  const auto* version = reinterpret_cast<const char*>(gl_.GetString(GL_VERSION));
  const auto* renderer = reinterpret_cast<const char*>(gl_.GetString(GL_RENDERER));
  description_ = std::string("OSMesa, ") + (renderer != nullptr ? renderer : "unknown renderer") +
                 ", OpenGL " + (version != nullptr ? version : "?");
  return Status::Ok();
}

OsmesaContext::~OsmesaContext() {
  if (context_ != nullptr) Symbol<DestroyContext>(library_, "OSMesaDestroyContext")(context_);
  if (library_ != nullptr) dlclose(library_);
}

Status OsmesaContext::MakeCurrent() {
  const auto make_current = Symbol<MakeCurrentFn>(library_, "OSMesaMakeCurrent");
  if (!make_current(context_, buffer_, kGlUnsignedByte, 1, 1)) {
    return Status(M4D_ERR_UNSUPPORTED, "gl: OSMesaMakeCurrent failed");
  }
  return Status::Ok();
}

void OsmesaContext::ReleaseCurrent() {
  Symbol<MakeCurrentFn>(library_, "OSMesaMakeCurrent")(nullptr, nullptr, 0, 0, 0);
}

}  // namespace m4d
