#include "gl_context.h"

#include <cstdlib>
#include <cstring>
#include <vector>

#include "vdg/geom/error.h"

namespace vdg::render::detail {
namespace {

std::string eglErrorName(EGLint code) {
  switch (code) {
    case EGL_SUCCESS:
      return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED:
      return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS:
      return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC:
      return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE:
      return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG:
      return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT:
      return "EGL_BAD_CONTEXT";
    case EGL_BAD_DISPLAY:
      return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH:
      return "EGL_BAD_MATCH";
    case EGL_BAD_PARAMETER:
      return "EGL_BAD_PARAMETER";
    case EGL_BAD_SURFACE:
      return "EGL_BAD_SURFACE";
    default:
      return "EGL error " + std::to_string(code);
  }
}

bool hasClientExtension(const char* name) {
  const char* list = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  if (!list) return false;
  const std::size_t n = std::strlen(name);
  for (const char* p = std::strstr(list, name); p; p = std::strstr(p + n, name))
    if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
  return false;
}

// Tries the headless platforms in order; returns an initialised display or EGL_NO_DISPLAY, and
// appends what failed to `tried`.
EGLDisplay openDisplay(std::string& platform, std::string& tried) {
  auto initialise = [&](EGLDisplay d, const char* name) {
    if (d == EGL_NO_DISPLAY) {
      tried += std::string(tried.empty() ? "" : "; ") + name + ": no display";
      return false;
    }
    EGLint major = 0, minor = 0;
    if (!eglInitialize(d, &major, &minor)) {
      tried += std::string(tried.empty() ? "" : "; ") + name + ": eglInitialize failed (" +
               eglErrorName(eglGetError()) + ")";
      return false;
    }
    platform = name;
    return true;
  };
  const bool platform_base = hasClientExtension("EGL_EXT_platform_base");
  if (platform_base && hasClientExtension("EGL_MESA_platform_surfaceless")) {
    EGLDisplay d = eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (initialise(d, "surfaceless")) return d;
  }
  if (platform_base && hasClientExtension("EGL_EXT_platform_device") &&
      hasClientExtension("EGL_EXT_device_enumeration")) {
    EGLint count = 0;
    eglQueryDevicesEXT(0, nullptr, &count);
    std::vector<EGLDeviceEXT> devices(static_cast<std::size_t>(count > 0 ? count : 0));
    if (count > 0 && eglQueryDevicesEXT(count, devices.data(), &count)) {
      for (EGLint i = 0; i < count; ++i) {
        EGLDisplay d = eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, devices[static_cast<std::size_t>(i)], nullptr);
        if (initialise(d, "device")) return d;
      }
    }
  }
  if (initialise(eglGetDisplay(EGL_DEFAULT_DISPLAY), "default")) return eglGetDisplay(EGL_DEFAULT_DISPLAY);
  return EGL_NO_DISPLAY;
}

}  // namespace

GlContext::GlContext() {
  if (const char* off = std::getenv("VDG_RENDER_NO_GL"); off && *off && std::strcmp(off, "0") != 0)
    throw Error("EGL: no display: OpenGL disabled by VDG_RENDER_NO_GL");
  std::string tried;
  display_ = openDisplay(platform_, tried);
  if (display_ == EGL_NO_DISPLAY)
    throw Error("EGL: no display (tried " + (tried.empty() ? std::string("nothing: no EGL platform") : tried) +
                "); a GPU driver or Mesa's llvmpipe (libegl-mesa0) is needed");
  if (!eglBindAPI(EGL_OPENGL_API)) throw Error("EGL: desktop OpenGL not supported on the " + platform_ + " display");

  const EGLint config_attribs[] = {EGL_SURFACE_TYPE,
                                   EGL_PBUFFER_BIT,
                                   EGL_RENDERABLE_TYPE,
                                   EGL_OPENGL_BIT,
                                   EGL_RED_SIZE,
                                   8,
                                   EGL_GREEN_SIZE,
                                   8,
                                   EGL_BLUE_SIZE,
                                   8,
                                   EGL_NONE};
  EGLConfig config = nullptr;
  EGLint configs = 0;
  if (!eglChooseConfig(display_, config_attribs, &config, 1, &configs) || configs < 1) {
    const EGLint any_surface[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE, 0, EGL_NONE};
    if (!eglChooseConfig(display_, any_surface, &config, 1, &configs) || configs < 1)
      throw Error("EGL: no OpenGL-capable config on the " + platform_ + " display");
  }
  const int versions[][2] = {{4, 5}, {3, 3}};
  for (const auto& v : versions) {
    const EGLint attribs[] = {
        EGL_CONTEXT_MAJOR_VERSION,           v[0],    EGL_CONTEXT_MINOR_VERSION, v[1], EGL_CONTEXT_OPENGL_PROFILE_MASK,
        EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
    context_ = eglCreateContext(display_, config, EGL_NO_CONTEXT, attribs);
    if (context_ != EGL_NO_CONTEXT) break;
  }
  if (context_ == EGL_NO_CONTEXT)
    throw Error("EGL: cannot create an OpenGL 3.3 core context on the " + platform_ + " display (" +
                eglErrorName(eglGetError()) + ")");
  if (!epoxy_has_egl_extension(display_, "EGL_KHR_surfaceless_context")) {
    const EGLint pbuffer[] = {EGL_WIDTH, 1, EGL_HEIGHT, 1, EGL_NONE};
    surface_ = eglCreatePbufferSurface(display_, config, pbuffer);
    if (surface_ == EGL_NO_SURFACE) {
      eglDestroyContext(display_, context_);
      throw Error("EGL: cannot create a pbuffer surface (" + eglErrorName(eglGetError()) + ")");
    }
  }
  if (!eglMakeCurrent(display_, surface_, surface_, context_)) {
    const std::string reason = eglErrorName(eglGetError());
    if (surface_ != EGL_NO_SURFACE) eglDestroySurface(display_, surface_);
    eglDestroyContext(display_, context_);
    throw Error("EGL: cannot make the OpenGL context current (" + reason + ")");
  }
}

GlContext::~GlContext() {
  // The display is shared by every context of the process (EGL returns the same handle), so it
  // is not terminated here: another renderer may still use it.
  if (eglGetCurrentContext() == context_) eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  if (surface_ != EGL_NO_SURFACE) eglDestroySurface(display_, surface_);
  eglDestroyContext(display_, context_);
}

void GlContext::makeCurrent() const {
  if (eglGetCurrentContext() != context_) eglMakeCurrent(display_, surface_, surface_, context_);
}

}  // namespace vdg::render::detail
