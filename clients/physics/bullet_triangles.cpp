#include "clients/physics/bullet_triangles.hpp"

namespace thx::phys {

std::unique_ptr<BulletTriangles> bulletTriangles(const mesh::TexturedMesh& mesh) {
  auto t = std::make_unique<BulletTriangles>();
  t->indices.reserve(3 * mesh.triangles.size());
  for (const mesh::Triangle& triangle : mesh.triangles)
    for (std::uint32_t v : triangle) t->indices.push_back(int(v));
  t->vertices.reserve(3 * mesh.positions.size());
  for (const Eigen::Vector3d& p : mesh.positions)
    for (int k = 0; k < 3; ++k) t->vertices.push_back(btScalar(p[k]));
  t->array = std::make_unique<btTriangleIndexVertexArray>(int(mesh.triangles.size()), t->indices.data(),
                                                          int(3 * sizeof(int)), int(mesh.positions.size()),
                                                          t->vertices.data(), int(3 * sizeof(btScalar)));
  return t;
}

}  // namespace thx::phys
