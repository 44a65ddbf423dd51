#pragma once
// The second presenter: a GLFW window (a real X server or Xvfb) showing the framebuffer the one
// render path fills (blit, then swap). Keys: N / R / M switch normal / relief / mesh, S toggles
// self-shadowing, X relief's search (linear / maxmip), arrows turn the camera (azimuth, elevation), + / - move it nearer / farther,
// Esc or Q closes. A frame is drawn only when something changed.
#include <functional>
#include <string>
#include <vector>

#include "clients/visual/camera.hpp"
#include "clients/visual/object_renderer.hpp"
#include "clients/visual/render_settings.hpp"
#include "textures/textured_surface.hpp"

namespace thx::visual {

struct WindowOptions {
  int width = 640, height = 360;
  int max_frames = 0;  // > 0: close after this many drawn frames (tests, scripted runs under Xvfb)
  double max_seconds = 0;  // > 0: close after this long (live --duration)
  bool quiet = false;
  std::string screenshot;  // with max_frames: the window's last frame, read back from the window
  // Live (--live): called every 1/live_rate_hz s with the objects shown and the surface; it
  // updates them and says whether a frame is due (Same: nothing moved, no frame). Frames also
  // wait for the display (swap interval 1), so they never come faster than it refreshes.
  enum class LiveChange { Same, Moved, NewSurface };
  std::function<LiveChange(std::vector<ObjectInstance>& objects, const tex::TexturedSurface*& surface)> live_update;
  double live_rate_hz = 30.0;
  std::function<bool()> stop;  // optional: true closes the window (live: SIGINT / SIGTERM)
};

// Throws GlError when there is no display ("DISPLAY is not set: run under xvfb-run ...") or
// GLFW cannot create a 3.3 core context. Returns the number of frames drawn.
int runWindow(const tex::TexturedSurface& surface, RenderSettings settings, CameraPlacement camera,
              const std::vector<ObjectInstance>& objects, const WindowOptions& options);

}  // namespace thx::visual
