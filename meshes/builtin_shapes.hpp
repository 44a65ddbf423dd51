#pragma once
// The built-in shapes a scene (surface.mesh.generator, docs/scenes.md) or visual-client
// (--surface-mesh) names, built by the generators (mesh_generators.hpp) from one size: `size_m`
// is the radius (sphere, cylinder, the torus's major radius, the bowl's and the vase's widest
// radius), `tile_m` the metres one texture tile spans (the generators round it to whole tiles
// around a closed loop), `segments` the divisions around the axis (the other directions follow).
#include <Eigen/Core>
#include <string>

#include "meshes/mesh_generators.hpp"

namespace thx::mesh {

// "sphere|cylinder|torus|bowl|vase|box|room|plate", for help texts and errors.
extern const char* const kBuiltInShapes;
// 128 segments around: a silhouette of a 5 cm radius is then within 0.15 mm of the circle.
constexpr int kDefaultShapeSegments = 128;

bool isBuiltInShape(const std::string& shape);
// Throws thx::Error (Config) for a shape not in kBuiltInShapes or segments outside [8, 4096].
//   sphere    radius s, n segments x n/2 rings
//   cylinder  radius s, height 2 s, n segments x n/4 rows (an open tube)
//   torus     major radius s, minor radius 0.4 s, n x 3n/8
//   bowl      radius s, height 0.8 s, wall 0.08 s, turned with n segments (profile 3n/8 samples)
//   vase      height 2.4 s, widest radius s, wall 0.06 s, turned with n segments (profile n/2)
//   box       a cube of side 2 s, each face n/16 x n/16 cells (at least 1)
//   room      the inside of that cube (its faces face inward: three meet at each inside corner)
//   plate     2 s x 2 s, 0.05 s thick (1 mm for s = 2 cm), cells as the box's
// Bowl, vase and cylinder stand on z = 0; the others are centred on the origin.
GeneratedMesh builtInShape(const std::string& shape, double size_m, double tile_m,
                           int segments = kDefaultShapeSegments);

// The centre of the mesh's bounding box (the point a camera orbits).
Eigen::Vector3d boundsCentre(const TexturedMesh& mesh);

}  // namespace thx::mesh
