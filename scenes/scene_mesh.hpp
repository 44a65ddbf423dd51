#pragma once
// The scene's surface mesh (surface.mesh, docs/scenes.md), built one way for every program that
// feels or shows it (hapticd, visual-client, the tools): the built-in shape or the mesh file,
// checked (meshes/mesh_check.hpp, with the scene's triangle bound and closedness) and given its
// vertex frames, placed in the surface frame by its own pose and in the world by the surface's. The texture is the scene's surface
// texture (scene_surface.hpp), wrapped through the mesh's texture coordinates.
// Configuration time only: reads files, allocates, throws.
#include <Eigen/Geometry>
#include <cstdint>

#include "meshes/textured_mesh.hpp"
#include "scenes/scene.hpp"

namespace thx::scene {

struct SceneMesh {
  mesh::TexturedMesh mesh;           // in its own frame (the surface frame), vertex frames built
  Eigen::Isometry3d mesh_to_world = Eigen::Isometry3d::Identity();  // the surface's pose x the mesh's
  // Metres per uv unit along u and v: a generated shape's tile (rounded to whole tiles around it),
  // a file's surface.size (what the texture's extent is made for; the file's uv sets the scale).
  Eigen::Vector2d tile_m{0.0, 0.0};
};

// Requires scene.surface.mesh. Throws SceneError located at the scene's `mesh:` field, quoting
// the mesh reader's or the checks' message (which names the file and the element).
SceneMesh buildSceneMesh(const Scene& scene);

// What hello_t.texture_fingerprint carries for a mesh scene: the scene surface's texture
// fingerprint (scene_surface.hpp) hashed with the mesh as every sense reads it, so two hosts whose
// mesh files (or generators) differ see different fingerprints. FNV-1a 64 (base/fnv1a64.hpp) over
// the tag "thx.mesh.v1"; the texture fingerprint (uint64); the position and triangle counts
// (int32); for each vertex in turn its position x, y, z and its uv u, v (quantised to 1e-12);
// every triangle's three vertex indices (int32); mesh_to_world's rotation row by row and its
// translation; the tile u, v.
// The positions and uv are those after the vertex frames were built (a split vertex counts twice).
std::uint64_t meshSceneFingerprint(std::uint64_t texture_fingerprint, const mesh::TexturedMesh& mesh,
                                   const Eigen::Isometry3d& mesh_to_world, const Eigen::Vector2d& tile_m);
inline std::uint64_t meshSceneFingerprint(std::uint64_t texture_fingerprint, const SceneMesh& m) {
  return meshSceneFingerprint(texture_fingerprint, m.mesh, m.mesh_to_world, m.tile_m);
}

}  // namespace thx::scene
