#pragma once
// A frame of a textured mesh and the objects given (the pen of a recorded session), into a
// Framebuffer as FrameRenderer draws the plane's frames; glFinish, so a following read or a timing
// is of this frame.
#include <memory>
#include <vector>

#include "clients/visual/framebuffer.hpp"
#include "clients/visual/mesh_surface_renderer.hpp"
#include "clients/visual/object_renderer.hpp"
#include "clients/visual/textured_object_renderer.hpp"

namespace thx::visual {

class MeshFrameRenderer {
 public:
  MeshFrameRenderer(const MeshSurface& surface, const RenderSettings& settings, int width, int height);
  void render(const Camera& camera, const std::vector<ObjectInstance>& objects = {});
  // The scene's textured objects (objects[].texture) are drawn textured from now on; without
  // this they are drawn as plain boxes. Throws scene::SceneError for a texture that fails to build.
  void setTexturedObjects(const scene::Scene& scene) {
    textured_objects_ = std::make_unique<TexturedObjectRenderer>(scene, settings_);
  }
  const Framebuffer& framebuffer() const { return framebuffer_; }
  const RenderSettings& settings() const { return settings_; }

 private:
  RenderSettings settings_;
  Framebuffer framebuffer_;
  MeshSurfaceRenderer surface_renderer_;
  ObjectRenderer object_renderer_;
  std::unique_ptr<TexturedObjectRenderer> textured_objects_;
  Eigen::Matrix3d mesh_to_world_rotation_;  // the light is given in the mesh's frame
};

}  // namespace thx::visual
