// Headless EGL + OpenGL core context (private to the render module). See renderer.h for the
// platform order and the VDG_RENDER_NO_GL switch.
#pragma once

#include <epoxy/egl.h>

#include <string>

namespace vdg::render::detail {

class GlContext {
 public:
  // Throws vdg::Error "EGL: ..." naming the step that failed.
  GlContext();
  ~GlContext();
  GlContext(const GlContext&) = delete;
  GlContext& operator=(const GlContext&) = delete;

  // Makes this context current on the calling thread (cheap when it already is).
  void makeCurrent() const;
  const std::string& platform() const { return platform_; }

 private:
  EGLDisplay display_ = EGL_NO_DISPLAY;
  EGLContext context_ = EGL_NO_CONTEXT;
  EGLSurface surface_ = EGL_NO_SURFACE;  // 1x1 pbuffer, only without EGL_KHR_surfaceless_context
  std::string platform_;
};

}  // namespace vdg::render::detail
