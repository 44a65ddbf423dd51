#pragma once
// A frame of a textured mesh alone (no objects, no pen: they rest on the plane the mesh replaces),
// into a Framebuffer as FrameRenderer draws the plane's frames; glFinish, so a following read or
// a timing is of this frame.
#include "clients/visual/framebuffer.hpp"
#include "clients/visual/mesh_surface_renderer.hpp"

namespace thx::visual {

class MeshFrameRenderer {
 public:
  MeshFrameRenderer(const MeshSurface& surface, const RenderSettings& settings, int width, int height);
  void render(const Camera& camera);
  const Framebuffer& framebuffer() const { return framebuffer_; }
  const RenderSettings& settings() const { return settings_; }

 private:
  RenderSettings settings_;
  Framebuffer framebuffer_;
  MeshSurfaceRenderer surface_renderer_;
};

}  // namespace thx::visual
