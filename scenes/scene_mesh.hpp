#pragma once
// The scene's surface mesh (surface.mesh, docs/scenes.md), built one way for every program that
// feels or shows it (hapticd, visual-client, the tools): the built-in shape or the mesh file,
// checked (meshes/mesh_check.hpp, with the scene's triangle bound and closedness) and given its
// vertex frames, placed in the surface frame by its own pose and in the world by the surface's. The texture is the scene's surface
// texture (scene_surface.hpp), wrapped through the mesh's texture coordinates.
// Configuration time only: reads files, allocates, throws.
#include <Eigen/Geometry>

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

}  // namespace thx::scene
