#pragma once
// A scene whose surface is a textured mesh (surface.mesh, docs/scenes.md), made ready for the
// servo off its thread: the mesh (scenes/scene_mesh.hpp), its flat triangles and their hierarchy
// (MeshGeometry, shared read-only by the scene's renderer and the simulated hand's height source),
// and the renderer that runs in the servo tick (textured_mesh_renderer.hpp) with the scene's
// texture wrapped through the mesh's uv. Configuration time only: allocates, reads files, throws.
#include <memory>

#include "scenes/scene.hpp"
#include "scenes/scene_mesh.hpp"
#include "server/mesh_surface_height.hpp"
#include "server/textured_mesh_renderer.hpp"
#include "server/triangle_bvh.hpp"
#include "server/triangle_mesh.hpp"
#include "textures/textured_surface.hpp"

namespace thx::srv {

// Immovable (the hierarchy points at the mesh's arrays): held by a shared_ptr, built by
// buildMeshGeometry.
struct MeshGeometry {
  explicit MeshGeometry(scene::SceneMesh built);
  MeshGeometry(const MeshGeometry&) = delete;
  MeshGeometry& operator=(const MeshGeometry&) = delete;

  scene::SceneMesh scene_mesh;  // the mesh in its frame, its pose, its texture tile
  TriangleBvh bvh;              // over the mesh's positions and triangles
};

// Throws scene::SceneError (surface.mesh) for the mesh's errors, thx::Error for the hierarchy's.
std::shared_ptr<const MeshGeometry> buildMeshGeometry(const scene::Scene& scene);

// The simulated hand's heights over the scene's mesh, seen from above in the surface frame (the
// frame its script works in, device/hand_script.hpp). The mesh must outlive it.
std::unique_ptr<MeshSurfaceHeight> handSurfaceFor(const scene::Scene& scene, const MeshGeometry& mesh);

// The servo's renderer for the mesh with `surface`'s texture map and sampling (its plane mapping is
// not used), relief read as displacement when the surface uses it. Both must outlive the renderer.
std::unique_ptr<TexturedMeshRenderer> buildMeshRenderer(const MeshGeometry& geometry,
                                                        const tex::TexturedSurface& surface,
                                                        const RendererConfig& config);

}  // namespace thx::srv
