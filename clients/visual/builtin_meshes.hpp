#pragma once
// The textured meshes visual-client can draw instead of the plane (--surface-mesh), built by the
// meshes library's generators at one size: `size_m` is the radius (sphere, cylinder, the torus's
// major radius, the bowl's and the vase's widest radius), `tile_m` the metres one texture tile
// spans (the generators round it to whole tiles around a closed loop).
#include <Eigen/Core>
#include <string>

#include "meshes/mesh_generators.hpp"

namespace thx::visual {

// "sphere|cylinder|torus|bowl|vase", for help texts and errors.
extern const char* const kBuiltInMeshShapes;

bool isBuiltInMesh(const std::string& shape);
// Throws thx::Error (Config) for a shape not in kBuiltInMeshShapes.
//   sphere    radius s, 128 segments x 64 rings
//   cylinder  radius s, height 2 s, 128 segments x 32 rows (an open tube)
//   torus     major radius s, minor radius 0.4 s, 128 x 48
//   bowl      radius s, height 0.8 s, wall 0.08 s, turned with 128 segments
//   vase      height 2.4 s, widest radius s, wall 0.06 s, turned with 128 segments
mesh::GeneratedMesh builtInMesh(const std::string& shape, double size_m, double tile_m);

// The centre of the mesh's bounding box (the point a camera orbits).
Eigen::Vector3d boundsCentre(const mesh::TexturedMesh& mesh);

}  // namespace thx::visual
