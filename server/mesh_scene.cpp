#include "server/mesh_scene.hpp"

#include "scenes/scene_frames.hpp"

namespace thx::srv {

MeshGeometry::MeshGeometry(scene::SceneMesh built)
    : scene_mesh(std::move(built)), bvh(scene_mesh.mesh.positions, scene_mesh.mesh.triangles) {}

std::shared_ptr<const MeshGeometry> buildMeshGeometry(const scene::Scene& scene) {
  return std::make_shared<const MeshGeometry>(scene::buildSceneMesh(scene));
}

std::unique_ptr<MeshSurfaceHeight> handSurfaceFor(const scene::Scene& scene, const MeshGeometry& mesh) {
  return std::make_unique<MeshSurfaceHeight>(
      mesh.bvh, scene::planeMapping(scene.surface).plane_to_world.inverse() * mesh.scene_mesh.mesh_to_world);
}

std::unique_ptr<TexturedMeshRenderer> buildMeshRenderer(const MeshGeometry& geometry,
                                                        const tex::TexturedSurface& surface,
                                                        const RendererConfig& config) {
  MeshTexture texture;
  texture.map = &surface.map();
  texture.sampling = surface.sampling();
  texture.use_relief = surface.usesRelief();
  texture.normals_made_for_m = surface.mapping().size_m;  // the scene's tile (surface.size)
  texture.slope_steps = surface.slopeSteps();
  return std::make_unique<TexturedMeshRenderer>(geometry.scene_mesh.mesh, geometry.bvh, texture,
                                                geometry.scene_mesh.mesh_to_world, config);
}

}  // namespace thx::srv
