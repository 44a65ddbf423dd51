#pragma once
// Draws a textured triangle mesh (mesh_surface.hpp) in normal or relief mode
// (shaders/mesh_surface.frag): the plane's texture upload (texture_upload.hpp), lighting and
// relief search, in the tangent frames the haptic renderer uses. Relief uses the linear + binary
// search (the max-mipmap walk is the plane's); the displaced-grid mode is the plane's only.
#include <memory>

#include "clients/visual/camera.hpp"
#include "clients/visual/gpu_textured_mesh.hpp"
#include "clients/visual/mesh_surface.hpp"
#include "clients/visual/render_settings.hpp"
#include "clients/visual/shader_program.hpp"
#include "clients/visual/texture_upload.hpp"

namespace thx::visual {

class MeshSurfaceRenderer {
 public:
  // Needs a current GL context. Throws thx::Error (Config) for a mode or search the mesh does not
  // draw, or an incomplete MeshSurface. The light's angles are read in the mesh's frame.
  MeshSurfaceRenderer(const MeshSurface& surface, const RenderSettings& settings);
  void draw(const Camera& camera) const;
  // The mesh placed at `mesh_to_world` instead of the surface's own place, lit from `light_mesh`
  // (unit, towards the light, in the mesh's frame): a moving textured object.
  void draw(const Camera& camera, const Eigen::Isometry3d& mesh_to_world, const Eigen::Vector3d& light_mesh) const;

 private:
  MeshSurface surface_;
  RenderSettings settings_;
  std::unique_ptr<ShaderProgram> program_;
  std::unique_ptr<SurfaceTexture> texture_;
  std::unique_ptr<GpuTexturedMesh> mesh_;
};

}  // namespace thx::visual
