#include "meshes/builtin_shapes.hpp"

#include <Eigen/Geometry>

#include <algorithm>

#include "base/error.hpp"

namespace thx::mesh {

const char* const kBuiltInShapes = "sphere|cylinder|torus|bowl|vase|box|room|plate";

bool isBuiltInShape(const std::string& shape) {
  for (const char* name : {"sphere", "cylinder", "torus", "bowl", "vase", "box", "room", "plate"})
    if (shape == name) return true;
  return false;
}

GeneratedMesh builtInShape(const std::string& shape, double s, double tile_m, int n) {
  if (n < 8 || n > 4096)
    throw Error(Error::Kind::Config,
                "textured mesh '" + shape + "': segments " + std::to_string(n) + " outside [8, 4096]");
  if (shape == "sphere") return sphere(s, n, n / 2, tile_m);
  if (shape == "cylinder") return cylinder(s, 2 * s, n, n / 4, tile_m);
  if (shape == "torus") return torus(s, 0.4 * s, n, 3 * n / 8, tile_m);
  if (shape == "bowl") return lathe(bowlProfile(s, 0.8 * s, 0.08 * s, 3 * n / 8), n, tile_m);
  if (shape == "vase") return lathe(vaseProfile(2.4 * s, s, 0.06 * s, n / 2), n, tile_m);
  // The flat shapes: a cell of 2 s / (n / 16), 8 cells along a side at the default n.
  const double cell = 2 * s / std::max(1, n / 16);
  if (shape == "box") return box(Eigen::Vector3d::Constant(2 * s), cell, tile_m);
  if (shape == "room") return box(Eigen::Vector3d::Constant(2 * s), cell, tile_m, /*inward=*/true);
  if (shape == "plate") return box(Eigen::Vector3d(2 * s, 2 * s, 0.05 * s), cell, tile_m);
  throw Error(Error::Kind::Config, "textured mesh '" + shape + "': expected one of " + kBuiltInShapes);
}

Eigen::Vector3d boundsCentre(const TexturedMesh& mesh) {
  Eigen::AlignedBox3d box;
  for (const Eigen::Vector3d& p : mesh.positions) box.extend(p);
  return box.isEmpty() ? Eigen::Vector3d::Zero().eval() : box.center().eval();
}

}  // namespace thx::mesh
