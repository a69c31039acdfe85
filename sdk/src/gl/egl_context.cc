#include "sdk/src/gl/egl_context.h"

// Headless: keep the X11 headers out of eglplatform.h.
#define EGL_NO_X11 1
#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstdio>
#include <cstring>

namespace m4d {
namespace {

bool HasExtension(const char* list, const char* name) {
  if (list == nullptr) return false;
  const size_t n = std::strlen(name);
  for (const char* p = std::strstr(list, name); p != nullptr; p = std::strstr(p + n, name)) {
    const bool starts = p == list || p[-1] == ' ';
    const bool ends = p[n] == '\0' || p[n] == ' ';
    if (starts && ends) return true;
  }
  return false;
}

std::string EglErrorText(const char* what) {
  char text[96];
  std::snprintf(text, sizeof(text), "%s failed (EGL error 0x%04X)", what,
                static_cast<unsigned>(eglGetError()));
  return text;
}

// Mesa's surfaceless platform: no window system, no device files needed. EGL_NO_DISPLAY and
// a reason when the EGL library does not offer it or cannot initialise it.
EGLDisplay OpenSurfacelessDisplay(std::string* reason) {
  // Client extensions; NULL from an EGL without the extension mechanism.
  const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  if (!HasExtension(client, "EGL_EXT_platform_base") ||
      !HasExtension(client, "EGL_MESA_platform_surfaceless")) {
    *reason = "surfaceless platform not offered";
    return EGL_NO_DISPLAY;
  }
  const auto get_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
      eglGetProcAddress("eglGetPlatformDisplayEXT"));
  if (get_display == nullptr) {
    *reason = "eglGetPlatformDisplayEXT missing";
    return EGL_NO_DISPLAY;
  }
  EGLDisplay display = get_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  if (display == EGL_NO_DISPLAY || !eglInitialize(display, nullptr, nullptr)) {
    *reason = "surfaceless " + EglErrorText("eglInitialize");
    return EGL_NO_DISPLAY;
  }
  return display;
}

EGLDisplay OpenDefaultDisplay(std::string* reason) {
  EGLDisplay display = eglGetDisplay(EGL_DEFAULT_DISPLAY);
  if (display == EGL_NO_DISPLAY || !eglInitialize(display, nullptr, nullptr)) {
    *reason = "default display " + EglErrorText("eglInitialize");
    return EGL_NO_DISPLAY;
  }
  return display;
}

}  // namespace

Status EglContext::Create(std::unique_ptr<EglContext>* context) {
  std::unique_ptr<EglContext> created(new EglContext());
  M4D_RETURN_IF_ERROR(created->Initialize());
  *context = std::move(created);
  return Status::Ok();
}

Status EglContext::Initialize() {
  std::string surfaceless_reason, default_reason;
  const char* kind = "surfaceless";
  display_ = OpenSurfacelessDisplay(&surfaceless_reason);
  if (display_ == EGL_NO_DISPLAY) {
    kind = "default display";
    display_ = OpenDefaultDisplay(&default_reason);
  }
  if (display_ == EGL_NO_DISPLAY) {
    return Status(M4D_ERR_UNSUPPORTED,
                  "gl: no EGL display (" + surfaceless_reason + "; " + default_reason + ")");
  }
  if (!eglBindAPI(EGL_OPENGL_ES_API)) {
    return Status(M4D_ERR_UNSUPPORTED, "gl: " + EglErrorText("eglBindAPI(OpenGL ES)"));
  }
  // Rendering goes to framebuffer objects; the configuration only has to allow a pbuffer.
  const EGLint config_attribs[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE,
                                   EGL_OPENGL_ES3_BIT, EGL_NONE};
  EGLConfig config = nullptr;
  EGLint config_count = 0;
  if (!eglChooseConfig(display_, config_attribs, &config, 1, &config_count) || config_count < 1) {
    return Status(M4D_ERR_UNSUPPORTED, "gl: the EGL display has no OpenGL ES 3 configuration");
  }
  const EGLint context_attribs[] = {EGL_CONTEXT_CLIENT_VERSION, 3, EGL_NONE};
  context_ = eglCreateContext(display_, config, EGL_NO_CONTEXT, context_attribs);
  if (context_ == EGL_NO_CONTEXT) {
    return Status(M4D_ERR_UNSUPPORTED, "gl: " + EglErrorText("eglCreateContext(OpenGL ES 3)"));
  }
  if (!HasExtension(eglQueryString(display_, EGL_EXTENSIONS), "EGL_KHR_surfaceless_context")) {
    const EGLint pbuffer_attribs[] = {EGL_WIDTH, 1, EGL_HEIGHT, 1, EGL_NONE};
    surface_ = eglCreatePbufferSurface(display_, config, pbuffer_attribs);
    if (surface_ == EGL_NO_SURFACE) {
      return Status(M4D_ERR_UNSUPPORTED, "gl: " + EglErrorText("eglCreatePbufferSurface"));
    }
  }
  M4D_RETURN_IF_ERROR(MakeCurrent());
  M4D_RETURN_IF_ERROR(LoadGlFunctions(eglGetProcAddress, &gl_));
  const auto* version = reinterpret_cast<const char*>(gl_.GetString(GL_VERSION));
  if (version == nullptr || std::strncmp(version, "OpenGL ES 3", 11) != 0) {
    return Status(M4D_ERR_UNSUPPORTED, std::string("gl: context is not OpenGL ES 3: ") +
                                           (version != nullptr ? version : "(no version)"));
  }
  const auto* renderer = reinterpret_cast<const char*>(gl_.GetString(GL_RENDERER));
  description_ = std::string(kind) + ", " + (renderer != nullptr ? renderer : "unknown renderer");
  return Status::Ok();
}

EglContext::~EglContext() {
  if (display_ == EGL_NO_DISPLAY) return;
  if (context_ != EGL_NO_CONTEXT) {
    if (eglGetCurrentContext() == context_) ReleaseCurrent();
    eglDestroyContext(display_, context_);
  }
  if (surface_ != EGL_NO_SURFACE) eglDestroySurface(display_, surface_);
  // No eglTerminate: it acts on the whole display, which every context of the process on the
  // same platform shares, and would pull the display from under the others.
}

Status EglContext::MakeCurrent() {
  if (!eglMakeCurrent(display_, surface_, surface_, context_)) {
    return Status(M4D_ERR_UNSUPPORTED, "gl: " + EglErrorText("eglMakeCurrent"));
  }
  return Status::Ok();
}

void EglContext::ReleaseCurrent() {
  eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
}

}  // namespace m4d
