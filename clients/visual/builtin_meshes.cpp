#include "clients/visual/builtin_meshes.hpp"

#include "base/error.hpp"

namespace thx::visual {

const char* const kBuiltInMeshShapes = "sphere|cylinder|torus|bowl|vase";

bool isBuiltInMesh(const std::string& shape) {
  return shape == "sphere" || shape == "cylinder" || shape == "torus" || shape == "bowl" || shape == "vase";
}

mesh::GeneratedMesh builtInMesh(const std::string& shape, double s, double tile_m) {
  // 128 segments around: a silhouette of a 5 cm radius is then within 0.15 mm of the circle, and
  // 16,000 to 20,000 triangles draw in a few milliseconds on llvmpipe.
  constexpr int kAround = 128;
  if (shape == "sphere") return mesh::sphere(s, kAround, 64, tile_m);
  if (shape == "cylinder") return mesh::cylinder(s, 2 * s, kAround, 32, tile_m);
  if (shape == "torus") return mesh::torus(s, 0.4 * s, kAround, 48, tile_m);
  if (shape == "bowl") return mesh::lathe(mesh::bowlProfile(s, 0.8 * s, 0.08 * s, 48), kAround, tile_m);
  if (shape == "vase") return mesh::lathe(mesh::vaseProfile(2.4 * s, s, 0.06 * s, 64), kAround, tile_m);
  throw Error(Error::Kind::Config, "textured mesh '" + shape + "': expected one of " + kBuiltInMeshShapes);
}

Eigen::Vector3d boundsCentre(const mesh::TexturedMesh& mesh) {
  Eigen::AlignedBox3d box;
  for (const Eigen::Vector3d& p : mesh.positions) box.extend(p);
  return box.isEmpty() ? Eigen::Vector3d::Zero().eval() : box.center().eval();
}

}  // namespace thx::visual
