#include "clients/visual/headless_context.hpp"

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstdio>

#include "clients/visual/driver_pin.hpp"
#include "clients/visual/gl_api.hpp"
#include "clients/visual/gl_error.hpp"

namespace thx::visual {
namespace {

constexpr const char* kPackages =
    "install the EGL loader and Mesa's driver: apt-get install libegl1 libegl-mesa0 libgl1-mesa-dri "
    "(./setup.sh does)";

std::string eglFailure(const char* call) {
  char code[32];
  std::snprintf(code, sizeof code, "0x%04x", unsigned(eglGetError()));
  return std::string("headless OpenGL: ") + call + " failed (EGL error " + code + "); " + kPackages;
}

}  // namespace

HeadlessContext::HeadlessContext() {
  // The EGL 1.5 entry point: eglGetPlatformDisplayEXT is not exported for linking.
  EGLDisplay display = eglGetPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  if (display == EGL_NO_DISPLAY) throw GlError(eglFailure("eglGetPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA)"));
  EGLint major = 0, minor = 0;
  if (!eglInitialize(display, &major, &minor)) throw GlError(eglFailure("eglInitialize"));
  display_ = display;
  try {
    const EGLint config_attributes[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT,
                                        EGL_NONE};
    EGLConfig config = nullptr;
    EGLint configs = 0;
    if (!eglChooseConfig(display, config_attributes, &config, 1, &configs) || configs < 1)
      throw GlError(eglFailure("eglChooseConfig(OpenGL, pbuffer)"));
    if (!eglBindAPI(EGL_OPENGL_API)) throw GlError(eglFailure("eglBindAPI(EGL_OPENGL_API)"));
    EGLContext context = EGL_NO_CONTEXT;
    const EGLint wanted[][2] = {{4, 5}, {3, 3}};
    for (const auto& v : wanted) {
      const EGLint context_attributes[] = {EGL_CONTEXT_MAJOR_VERSION,       v[0],
                                           EGL_CONTEXT_MINOR_VERSION,       v[1],
                                           EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                           EGL_NONE};
      context = eglCreateContext(display, config, EGL_NO_CONTEXT, context_attributes);
      if (context != EGL_NO_CONTEXT) break;
    }
    if (context == EGL_NO_CONTEXT) throw GlError(eglFailure("eglCreateContext(OpenGL 3.3 core)"));
    context_ = context;
    if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context))
      throw GlError(eglFailure("eglMakeCurrent(surfaceless)"));
    pinGlDriver();
  } catch (...) {
    if (context_) eglDestroyContext(display, context_);
    eglTerminate(display);
    throw;
  }
}

HeadlessContext::~HeadlessContext() {
  eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  eglDestroyContext(display_, context_);
  eglTerminate(display_);
  eglReleaseThread();
}

std::string HeadlessContext::description() const {
  const auto text = [](GLenum name) {
    const GLubyte* s = glGetString(name);
    return s ? std::string(reinterpret_cast<const char*>(s)) : std::string("?");
  };
  return text(GL_RENDERER) + ", " + text(GL_VERSION);
}

}  // namespace thx::visual
