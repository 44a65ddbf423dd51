#pragma once
// A mesh scene's surface (surface.mesh, docs/scenes.md) as a sounding body: the solid its closed
// mesh encloses, tetrahedralised by Gmsh (surface_tetrahedra.hpp), in the mesh's own frame (the
// frame scenes/scene_mesh.hpp builds it in). A built-in shape is sounded at no more than
// kSoundSegments divisions around its axis: the haptic mesh's tessellation follows the texture
// (128 segments for the bowl of bricks, 27,392 triangles), the modes need far fewer, and Gmsh's
// tetrahedra grow with the boundary's triangles. A mesh file is sounded as it is.
// Not real-time code (reads files, runs Gmsh); part of thx_audio_tetra.
#include <Eigen/Geometry>
#include <string>

#include "clients/audio/analysis/scene_bodies.hpp"
#include "scenes/scene.hpp"

namespace thx::audio {

inline constexpr int kSoundSegments = 48;  // modal-analyze --mesh's default for a built-in shape

struct MeshSurfaceBody {
  SceneBody body;  // mesh.name "surface", the scene surface's material
  Eigen::Isometry3d mesh_to_world = Eigen::Isometry3d::Identity();  // the body's frame in the world
  std::size_t surface_triangles = 0;  // of the mesh tetrahedralised
};

// Requires scene.surface.mesh. Throws scene::SceneError (the mesh cannot be built) or ModalError
// (not closed, Gmsh cannot fill it: surface_tetrahedra.hpp) naming the scene's file.
MeshSurfaceBody meshSurfaceBody(const scene::Scene& scene, ElementOrder order = ElementOrder::Quadratic);

}  // namespace thx::audio
