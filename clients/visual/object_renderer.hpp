#pragma once
// Scene objects (spheres, boxes, cylinders, capsules) and the pen, as unit meshes placed by a
// model matrix, Blinn-Phong under the scene's light.
#include <Eigen/Geometry>
#include <memory>
#include <vector>

#include "clients/visual/camera.hpp"
#include "clients/visual/gpu_mesh.hpp"
#include "clients/visual/render_settings.hpp"
#include "clients/visual/shader_program.hpp"

namespace thx::visual {

enum class UnitShape { Sphere, Box, Cylinder };

struct ObjectInstance {
  UnitShape shape = UnitShape::Sphere;
  Eigen::Affine3d model = Eigen::Affine3d::Identity();  // unit shape -> world (includes scale)
  Eigen::Vector3f albedo{0.8f, 0.8f, 0.8f};
  char letter = 0;  // a letter block (box): this glyph (glyphs.hpp) on its ±z faces; 0 = none
  // A textured box (scene.objects[i].texture): i, and the body's pose (model without the scale).
  // A frame renderer given the scene's textured objects draws it through TexturedObjectRenderer
  // (textured_object_renderer.hpp); ObjectRenderer draws it as a plain box.
  int textured_object = -1;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
};

class ObjectRenderer {
 public:
  ObjectRenderer();  // needs a current GL context
  // `light_world`: unit, towards the light.
  void draw(const std::vector<ObjectInstance>& objects, const Camera& camera, const Eigen::Vector3d& light_world,
            const Lighting& light) const;

 private:
  std::unique_ptr<ShaderProgram> program_;
  std::unique_ptr<GpuMesh> sphere_, box_, cylinder_;
};

}  // namespace thx::visual
