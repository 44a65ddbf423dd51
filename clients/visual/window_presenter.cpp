#include "clients/visual/window_presenter.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>

#include "clients/visual/gl_api.hpp"
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include "clients/visual/driver_pin.hpp"
#include "clients/visual/frame_renderer.hpp"
#include "clients/visual/gl_error.hpp"
#include "clients/visual/image_writer.hpp"

namespace thx::visual {
namespace {

std::string glfwReason() {
  const char* description = nullptr;
  const int code = glfwGetError(&description);
  return (description ? std::string(description) : std::string("no description")) + " (GLFW error " +
         std::to_string(code) + ")";
}

// What the keys change; `dirty` asks for a new frame, `rebuild` for new shaders (another mode).
struct ViewState {
  RenderSettings settings;
  CameraPlacement camera;
  int shadow_steps_when_on = 8;
  bool dirty = true, rebuild = false;
};

void onKey(GLFWwindow* window, int key, int /*scancode*/, int action, int /*mods*/) {
  if (action == GLFW_RELEASE) return;
  auto* s = static_cast<ViewState*>(glfwGetWindowUserPointer(window));
  const auto mode = [s](SurfaceMode m) {
    s->rebuild = s->settings.mode != m;
    s->settings.mode = m;
  };
  switch (key) {
    case GLFW_KEY_ESCAPE:
    case GLFW_KEY_Q: glfwSetWindowShouldClose(window, GLFW_TRUE); return;
    case GLFW_KEY_N: mode(SurfaceMode::Normal); break;
    case GLFW_KEY_R: mode(SurfaceMode::Relief); break;
    case GLFW_KEY_M: mode(SurfaceMode::Mesh); break;
    case GLFW_KEY_S:
      s->settings.steps.shadow = s->settings.steps.shadow > 0 ? 0 : s->shadow_steps_when_on;
      s->rebuild = true;
      break;
    case GLFW_KEY_X:  // relief's search: linear <-> max-mipmap walk
      s->settings.steps.search =
          s->settings.steps.search == ReliefSearch::Linear ? ReliefSearch::MaxMip : ReliefSearch::Linear;
      s->rebuild = true;
      break;
    case GLFW_KEY_LEFT: s->camera.azimuth_deg -= 5; break;
    case GLFW_KEY_RIGHT: s->camera.azimuth_deg += 5; break;
    case GLFW_KEY_UP: s->camera.elevation_deg = std::min(90.0, s->camera.elevation_deg + 5); break;
    case GLFW_KEY_DOWN: s->camera.elevation_deg = std::max(1.0, s->camera.elevation_deg - 5); break;
    case GLFW_KEY_EQUAL:
    case GLFW_KEY_KP_ADD: s->camera.distance_m /= 1.2; break;
    case GLFW_KEY_MINUS:
    case GLFW_KEY_KP_SUBTRACT: s->camera.distance_m *= 1.2; break;
    default: return;
  }
  s->dirty = true;
}

struct GlfwSession {
  GlfwSession() {
    if (!glfwInit())
      throw GlError("window: GLFW cannot start: " + glfwReason() +
                    "; needs an X display (run under xvfb-run -a, Debian package xvfb) or use --screenshot / --frames");
  }
  ~GlfwSession() { glfwTerminate(); }
};

}  // namespace

int runWindow(const tex::TexturedSurface& first_surface, RenderSettings settings, CameraPlacement camera,
              const std::vector<ObjectInstance>& first_objects, const WindowOptions& options) {
  const tex::TexturedSurface* surface = &first_surface;
  std::vector<ObjectInstance> objects = first_objects;
  const char* display = std::getenv("DISPLAY");
  if (!display || !*display)
    throw GlError("window: DISPLAY is not set: run under xvfb-run -a (Debian package xvfb) or use --screenshot / --frames");
  const GlfwSession session;
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  std::unique_ptr<GLFWwindow, void (*)(GLFWwindow*)> window(
      glfwCreateWindow(options.width, options.height, "visual-client", nullptr, nullptr), &glfwDestroyWindow);
  if (!window) throw GlError("window: cannot create a 3.3 core window: " + glfwReason() + "; Debian: libgl1-mesa-dri");
  glfwMakeContextCurrent(window.get());
  pinGlDriver();
  glfwSwapInterval(1);

  ViewState state{settings, camera, settings.steps.shadow > 0 ? settings.steps.shadow : 8};
  glfwSetWindowUserPointer(window.get(), &state);
  glfwSetKeyCallback(window.get(), &onKey);

  int frames = 0;
  {
    auto renderer = std::make_unique<FrameRenderer>(*surface, state.settings, options.width, options.height);
    const auto start = std::chrono::steady_clock::now();
    const auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
    while (!glfwWindowShouldClose(window.get()) && !(options.max_seconds > 0 && elapsed() >= options.max_seconds) &&
           !(options.stop && options.stop())) {
      if (options.live_update) {
        const WindowOptions::LiveChange change = options.live_update(objects, surface);
        if (change != WindowOptions::LiveChange::Same) state.dirty = true;
        if (change == WindowOptions::LiveChange::NewSurface) state.rebuild = true;
      }
      if (state.rebuild) {
        renderer.reset();
        renderer = std::make_unique<FrameRenderer>(*surface, state.settings, options.width, options.height);
        state.rebuild = false;
      }
      if (state.dirty) {
        renderer->render(Camera(state.camera, surface->mapping().plane_to_world, options.width, options.height), objects);
        int fb_width = 0, fb_height = 0;
        glfwGetFramebufferSize(window.get(), &fb_width, &fb_height);
        renderer->framebuffer().bind();
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
        glBlitFramebuffer(0, 0, options.width, options.height, 0, 0, fb_width, fb_height, GL_COLOR_BUFFER_BIT,
                          GL_LINEAR);
        const bool last = options.max_frames > 0 && frames + 1 >= options.max_frames;
        if (last && !options.screenshot.empty()) writeImage(options.screenshot, readWindowBackBuffer(fb_width, fb_height));
        glfwSwapBuffers(window.get());
        checkGl("window present");
        // A scripted run (--window-frames) draws every frame; an interactive one only on change.
        state.dirty = options.max_frames > 0;
        ++frames;
        if (!options.quiet)
          std::fprintf(stderr, "\rvisual-client: %s%s, shadows %s, azimuth %.0f, elevation %.0f   ",
                       modeName(state.settings).c_str(),
                       state.settings.mode == SurfaceMode::Relief && state.settings.steps.search == ReliefSearch::MaxMip
                           ? " (maxmip)"
                           : "",
                       state.settings.steps.shadow > 0 ? "on" : "off",
                       state.camera.azimuth_deg, state.camera.elevation_deg);
        if (options.max_frames > 0 && frames >= options.max_frames) break;
      }
      // Nothing moves at rest: wait for a key rather than redraw the same frame; live, until the
      // next look at the streams.
      glfwWaitEventsTimeout(options.live_update ? 1.0 / options.live_rate_hz : 0.1);
    }
  }
  if (!options.quiet) std::fputc('\n', stderr);
  return frames;
}

}  // namespace thx::visual
