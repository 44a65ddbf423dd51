#pragma once
// Scene objects that carry a texture (objects[].texture: boxes with a relief map on their faces,
// balls with a bump map, issue 29), drawn with the textured mesh's shaders
// (mesh_surface_renderer.hpp) on a box or ball mesh laid out as the physics reads it
// (meshes/textured_box_mesh.hpp, meshes/textured_ball_mesh.hpp), each at its body's pose.
//
// Modes: the frame's own (normal or relief); the plane's displaced-grid mode and max-mipmap relief
// search have no mesh counterpart, so an object under them is drawn in relief mode with the linear
// search (at the frame's step counts).
#include <memory>
#include <vector>

#include "clients/visual/camera.hpp"
#include "clients/visual/mesh_surface_renderer.hpp"
#include "clients/visual/object_renderer.hpp"
#include "clients/visual/render_settings.hpp"
#include "meshes/textured_mesh.hpp"
#include "scenes/scene.hpp"
#include "textures/texture_map.hpp"

namespace thx::visual {

// The settings a textured object is drawn with under a frame's `settings` (above).
RenderSettings texturedObjectSettings(const RenderSettings& settings);

// The instances TexturedObjectRenderer does not draw (textured_object < 0).
std::vector<ObjectInstance> untexturedObjects(const std::vector<ObjectInstance>& objects);

class TexturedObjectRenderer {
 public:
  // Needs a current GL context. Builds every textured object's texture (scene::buildObjectTexture:
  // throws scene::SceneError for a bad one) and box mesh.
  TexturedObjectRenderer(const scene::Scene& scene, const RenderSettings& settings);
  ~TexturedObjectRenderer();
  // Draws the instances with textured_object >= 0 (others are left to ObjectRenderer);
  // `light_world`: unit, towards the light.
  void draw(const std::vector<ObjectInstance>& objects, const Camera& camera, const Eigen::Vector3d& light_world) const;
  bool empty() const { return objects_.empty(); }

 private:
  struct Textured;
  std::vector<std::unique_ptr<Textured>> objects_;  // indexed by scene object; null: not textured
};

}  // namespace thx::visual
