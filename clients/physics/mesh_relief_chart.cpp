#include "clients/physics/mesh_relief_chart.hpp"

#include <BulletCollision/BroadphaseCollision/btBroadphaseProxy.h>

#include <cmath>
#include <numbers>

namespace thx::phys {

namespace {

constexpr int kMeshReliefTag = 0x7468584d;  // "thXM": the user index marking an attached MeshRelief

// The bend's least-squares fit h = (xx x^2 + 2 xy x y + yy y^2) / 2 to the smooth surface's
// heights at eight points a distance `radius` round the foot (their feet on Phong's surface).
GroundBend fitBend(const ContactMesh& cm, const mesh::SurfaceFrame& f, std::uint32_t triangle, double radius) {
  Eigen::Matrix3d ata = Eigen::Matrix3d::Zero();
  Eigen::Vector3d atb = Eigen::Vector3d::Zero();
  for (int k = 0; k < 8; ++k) {
    const double a = k * std::numbers::pi / 4;
    const Eigen::Vector3d p = f.point + radius * (std::cos(a) * f.tangent + std::sin(a) * f.bitangent);
    std::uint32_t t = triangle;
    Eigen::Vector3d b(1.0 / 3, 1.0 / 3, 1.0 / 3);
    smoothFoot(cm, p, 1.0, t, b);
    const Eigen::Vector3d d = mesh::frameAt(*cm.mesh, t, b, mesh::FrameMode::InterpolatedPhong).point - f.point;
    const double x = d.dot(f.tangent), y = d.dot(f.bitangent), h = d.dot(f.normal);
    const Eigen::Vector3d row(0.5 * x * x, x * y, 0.5 * y * y);
    ata += row * row.transpose();
    atb += row * h;
  }
  const Eigen::Vector3d q = ata.ldlt().solve(atb);
  GroundBend bend;
  if (q.allFinite()) bend.xx = q[0], bend.xy = q[1], bend.yy = q[2];
  return bend;
}

}  // namespace

void attachMeshRelief(btCollisionShape& mesh_shape, const MeshRelief& relief) {
  mesh_shape.setUserPointer(const_cast<MeshRelief*>(&relief));
  mesh_shape.setUserIndex(kMeshReliefTag);
}

const MeshRelief* meshReliefOf(const btCollisionShape& shape) {
  if (shape.getShapeType() != TRIANGLE_MESH_SHAPE_PROXYTYPE || shape.getUserIndex() != kMeshReliefTag) return nullptr;
  return static_cast<const MeshRelief*>(shape.getUserPointer());
}

bool chartUnder(const MeshRelief& relief, const Eigen::Vector3d& c, double reach_m, std::uint32_t& triangle, MeshChart& out) {
  const mesh::TexturedMesh& m = *relief.mesh.mesh;
  if (triangle >= m.triangles.size()) triangle = mesh::nearestTriangle(m, c);
  Eigen::Vector3d b = mesh::closestBarycentric(m, triangle, c);
  // The winding's side first, then the foot along the smooth normal on that side.
  const mesh::SurfaceFrame near = mesh::frameAt(m, triangle, b, mesh::FrameMode::Interpolated);
  if ((c - near.point).dot(near.normal) < 0.0) return false;
  smoothFoot(relief.mesh, c, 1.0, triangle, b);
  const mesh::SurfaceFrame f = mesh::frameAt(m, triangle, b, mesh::FrameMode::InterpolatedPhong);
  if ((c - f.point).dot(f.normal) < 0.0) return false;
  // The chart as the pen's (hapticd's chartAt): x along the tangent, y along the bitangent, the
  // texture at this face's scale; uv taken within its tile so the chart's origin stays near.
  const Eigen::Vector2d scale = mesh::metresPerUv(m, triangle, f);
  const Eigen::Vector2d uv = f.uv - f.uv.array().floor().matrix();
  tex::PlaneMapping mapping;
  mapping.size_m = scale;
  Eigen::Matrix3d axes;
  axes.col(0) = f.tangent, axes.col(1) = f.bitangent, axes.col(2) = f.normal;
  mapping.plane_to_world.linear() = axes;
  const Eigen::Vector2d foot((uv.x() - 0.5) * scale.x(), (uv.y() - 0.5) * scale.y());
  mapping.plane_to_world.translation() = f.point - f.tangent * foot.x() - f.bitangent * foot.y();
  out.surface = tex::TexturedSurface(*relief.map, mapping, relief.sampling, true);
  out.surface.setNormalsMadeFor(relief.normals_made_for_m);
  out.bend = fitBend(relief.mesh, f, triangle, reach_m);
  out.bend.centre = foot;
  out.triangle = triangle;
  return true;
}

std::uint32_t triangleUnder(const MeshRelief& relief, const Eigen::Vector3d& p, std::uint32_t from) {
  Eigen::Vector3d b(1.0 / 3, 1.0 / 3, 1.0 / 3);
  smoothFoot(relief.mesh, p, 1.0, from, b);
  return from;
}

}  // namespace thx::phys
