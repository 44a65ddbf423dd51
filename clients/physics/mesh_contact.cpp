#include "clients/physics/mesh_contact.hpp"

#include <BulletCollision/BroadphaseCollision/btBroadphaseProxy.h>
#include <BulletCollision/CollisionShapes/btSphereShape.h>

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "clients/physics/bullet_convert.hpp"
#include "meshes/position_key.hpp"
#include "textures/textured_surface.hpp"

namespace thx::phys {


Eigen::Vector3d meshTextureNormal(const mesh::TexturedMesh& mesh, std::uint32_t triangle, const mesh::SurfaceFrame& f,
                                  Eigen::Vector3d n_tangent, const MeshContactOptions& options) {
  if (options.normals_made_for_m.minCoeff() > 0.0)
    n_tangent = tex::scaleSlopes(n_tangent, options.normals_made_for_m.cwiseQuotient(mesh::metresPerUv(mesh, triangle, f)));
  return clampTilt(mesh::fromTangentSpace(f, n_tangent), f.normal, options.max_tilt_deg);
}

double ballPatchRadius(double radius_m, double depth_m) {
  return depth_m > 0.0 && radius_m > 0.0 ? std::sqrt(2.0 * radius_m * depth_m) : 0.0;
}

Eigen::Vector3d meshContactNormal(const mesh::TexturedMesh& mesh, std::uint32_t triangle, const Eigen::Vector3d& b,
                                  const MeshContactOptions& options, double patch_radius_m) {
  const mesh::SurfaceFrame f = mesh::frameAt(mesh, triangle, b, mesh::FrameMode::Interpolated);
  if (!options.texture) return f.normal;
  const tex::TexCoord uv{f.uv.x(), f.uv.y()};
  if (options.pyramid != nullptr && patch_radius_m > 0.0) {
    // The patch's width in texels along the texture's more squeezed axis here (where a lathe's u
    // closes to a point, thousands): the level that averages that many.
    const Eigen::Vector2d metres_per_uv = mesh::metresPerUv(mesh, triangle, f);
    const double texels = 2.0 * patch_radius_m *
                          std::max(options.texture->width() / metres_per_uv.x(), options.texture->height() / metres_per_uv.y());
    if (texels > 1.0) {
      const Eigen::Vector3d n = options.pyramid->normal(uv, std::log2(texels), options.sampling.address);
      return meshTextureNormal(mesh, triangle, f, n, options);
    }
  }
  const tex::Sample s = tex::sample(*options.texture, uv, options.sampling);
  return meshTextureNormal(mesh, triangle, f, s.normal.cast<double>(), options);
}

ContactMesh::ContactMesh(const mesh::TexturedMesh& m) : mesh(&m), neighbours(mesh::triangleNeighbours(m)) {
  std::unordered_map<mesh::PositionBits, int, mesh::PositionHash> fan;
  for (const mesh::Triangle& t : m.triangles)
    for (std::uint32_t v : t) max_hops = std::max(max_hops, 16 + ++fan[mesh::bitsOf(m.positions[v])]);
}

void smoothFoot(const ContactMesh& contact_mesh, const Eigen::Vector3d& c, double side, std::uint32_t& triangle,
                Eigen::Vector3d& barycentric) {
  const mesh::TexturedMesh& mesh = *contact_mesh.mesh;
  // Fixed point: the centre's line along the interpolated normal meets the triangle's plane at
  // x; walk to the triangle that holds x; again from there (as the haptic anchor does,
  // server/textured_mesh_renderer.cpp). A ball's radius is large against a triangle's turn, so two or
  // three rounds settle it.
  constexpr int kRounds = 4;
  for (int round = 0; round < kRounds; ++round) {
    const Eigen::Vector3d n = side * mesh::frameAt(mesh, triangle, barycentric, mesh::FrameMode::Interpolated).normal;
    for (int hop = 0; hop < contact_mesh.max_hops; ++hop) {
      const mesh::Triangle& t = mesh.triangles[triangle];
      const Eigen::Vector3d& p0 = mesh.positions[t[0]];
      const Eigen::Vector3d e1 = mesh.positions[t[1]] - p0, e2 = mesh.positions[t[2]] - p0;
      const Eigen::Vector3d face = e1.cross(e2);
      const double denom = face.dot(n);
      if (std::fabs(denom) < 1e-3 * face.norm()) break;  // the line runs along this face: keep the last place
      const Eigen::Vector3d w = c - n * (face.dot(c - p0) / denom) - p0;
      const double inv = 1.0 / face.squaredNorm();
      const double l1 = w.cross(e2).dot(face) * inv, l2 = e1.cross(w).dot(face) * inv;
      const Eigen::Vector3d b(1.0 - l1 - l2, l1, l2);
      int worst = 0;
      for (int k = 1; k < 3; ++k) worst = b[k] < b[worst] ? k : worst;
      const std::uint32_t next = b[worst] < 0.0 ? contact_mesh.neighbours[triangle][std::size_t(worst)] : mesh::kNoNeighbour;
      if (next == mesh::kNoNeighbour) {
        barycentric = b[worst] < 0.0 ? mesh::closestBarycentric(mesh, triangle, w + p0) : b;
        break;
      }
      triangle = next;
    }
  }
}

void applyMeshContact(btManifoldPoint& point, bool mesh_is_b, const Eigen::Isometry3d& mesh_to_world,
                      const ContactMesh& contact_mesh, const btCollisionObject& other,
                      const MeshContactOptions& options, const StepContext& step) {
  if (!options.smooth) return;
  const mesh::TexturedMesh& mesh = *contact_mesh.mesh;
  const int index = mesh_is_b ? point.m_index1 : point.m_index0;
  if (index < 0 || std::size_t(index) >= mesh.triangles.size()) return;
  std::uint32_t triangle = std::uint32_t(index);
  const Eigen::Isometry3d world_to_mesh = mesh_to_world.inverse();
  const Eigen::Vector3d on_mesh = world_to_mesh * toEigen(mesh_is_b ? point.m_positionWorldOnB : point.m_positionWorldOnA);
  Eigen::Vector3d b = mesh::closestBarycentric(mesh, triangle, on_mesh);
  Eigen::Vector3d n_face, tangent;
  double handedness = 1.0;
  mesh::triangleFrame(mesh, triangle, n_face, tangent, handedness);
  // Bullet's normal points from B to A; towards the object it is that (mesh B) or its reverse.
  const Eigen::Vector3d towards_object = world_to_mesh.linear() * toEigen(point.m_normalWorldOnB) * (mesh_is_b ? 1.0 : -1.0);
  const double side = n_face.dot(towards_object) < 0.0 ? -1.0 : 1.0;  // -1: touched from behind (a bowl's inside)

  Eigen::Vector3d n_geometric = side * n_face;
  double patch_radius = 0.0;  // only a ball's patch is known: other shapes read one point
  const btCollisionShape* shape = other.getCollisionShape();
  if (shape->getShapeType() == SPHERE_SHAPE_PROXYTYPE) {
    const double r = double(static_cast<const btSphereShape*>(shape)->getRadius());
    if (options.texture) patch_radius = ballPatchRadius(r, options.texture->maxDepth());
    const Eigen::Vector3d c = world_to_mesh * toEigen(other.getWorldTransform().getOrigin());
    smoothFoot(contact_mesh, c, side, triangle, b);
    const mesh::SurfaceFrame smooth = mesh::frameAt(mesh, triangle, b, mesh::FrameMode::InterpolatedPhong);
    n_geometric = side * smooth.normal;
    point.m_distance1 = static_cast<btScalar>(n_geometric.dot(c - smooth.point) - r);
  }
  const Eigen::Vector3d n = side * meshContactNormal(mesh, triangle, b, options, patch_radius);
  steerContact(point, mesh_is_b, mesh_to_world.linear() * n, mesh_to_world.linear() * n_geometric, other,
               options.hold_height, step);
}

}  // namespace thx::phys
