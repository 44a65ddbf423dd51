#pragma once
// A frame of a textured mesh and the objects given (the pen of a recorded session), into a
// Framebuffer as FrameRenderer draws the plane's frames; glFinish, so a following read or a timing
// is of this frame.
#include <vector>

#include "clients/visual/framebuffer.hpp"
#include "clients/visual/mesh_surface_renderer.hpp"
#include "clients/visual/object_renderer.hpp"

namespace thx::visual {

class MeshFrameRenderer {
 public:
  MeshFrameRenderer(const MeshSurface& surface, const RenderSettings& settings, int width, int height);
  void render(const Camera& camera, const std::vector<ObjectInstance>& objects = {});
  const Framebuffer& framebuffer() const { return framebuffer_; }
  const RenderSettings& settings() const { return settings_; }

 private:
  RenderSettings settings_;
  Framebuffer framebuffer_;
  MeshSurfaceRenderer surface_renderer_;
  ObjectRenderer object_renderer_;
  Eigen::Matrix3d mesh_to_world_rotation_;  // the light is given in the mesh's frame
};

}  // namespace thx::visual
