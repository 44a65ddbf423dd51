// Which faces within an object's reach stand across a crease from its chart and get a chart of
// their own (clients/physics/chart_boundary.hpp): those of a surface the mesh turns to at a hard
// edge, not those a smooth surface curves round to.
#include <gtest/gtest.h>

#include <BulletCollision/CollisionShapes/btBvhTriangleMeshShape.h>

#include <cmath>
#include <cstdio>
#include <memory>

#include "clients/physics/bullet_triangles.hpp"
#include "clients/physics/chart_boundary.hpp"
#include "clients/physics/mesh_contact.hpp"
#include "meshes/mesh_generators.hpp"

namespace thx::phys::test::test_chart_boundary {
namespace {

// An object of this bounding radius (a 1 cm ball) and the breaking threshold beside it.
constexpr double kObjectRadius = 0.01, kThreshold = 0.5e-3;

struct Meshed {
  mesh::GeneratedMesh generated;
  ContactMesh contact;
  std::unique_ptr<BulletTriangles> triangles;
  btBvhTriangleMeshShape shape;
  explicit Meshed(mesh::GeneratedMesh g)
      : generated(std::move(g)),
        contact(generated.mesh),
        triangles(bulletTriangles(generated.mesh)),
        shape(triangles->array.get(), true) {}
};

// The boundary of the chart laid at the foot of `centre` on the smooth surface (its tangent plane
// there), as relief_collision.cpp lays it for an object of kObjectRadius; `chart_normal` gets the
// chart's normal.
ChartBoundary boundaryUnder(const Meshed& m, const Eigen::Vector3d& centre, Eigen::Vector3d* chart_normal = nullptr) {
  const mesh::TexturedMesh& mesh = m.generated.mesh;
  std::uint32_t triangle = mesh::nearestTriangle(mesh, centre);
  Eigen::Vector3d b = mesh::closestBarycentric(mesh, triangle, centre);
  smoothFoot(m.contact, centre, 1.0, triangle, b);
  const mesh::SurfaceFrame f = mesh::frameAt(mesh, triangle, b, mesh::FrameMode::Interpolated);
  Eigen::Isometry3d mesh_from_chart = Eigen::Isometry3d::Identity();
  mesh_from_chart.linear() << f.tangent, f.normal.cross(f.tangent), f.normal;
  mesh_from_chart.translation() = f.point;
  if (chart_normal) *chart_normal = f.normal;
  const mesh::Triangle& t = mesh.triangles[triangle];
  const Eigen::Vector3d middle = (mesh.positions[t[0]] + mesh.positions[t[1]] + mesh.positions[t[2]]) / 3.0;
  const double reach_radius = kObjectRadius + kThreshold;
  const Eigen::AlignedBox3d reach(centre - Eigen::Vector3d::Constant(reach_radius), centre + Eigen::Vector3d::Constant(reach_radius));
  return chartBoundary(m.shape, m.contact, mesh_from_chart, (mesh_from_chart.inverse() * middle).head<2>(), reach, centre,
                       reach_radius);
}

// A 1 cm ball recessed 0.5 mm pressed on a smooth 1 mm sphere mesh: faces 60 degrees and more round
// from its foot lie within its reach. They were taken for surfaces across a crease, and their
// charts (tangent planes run on far past the sphere) read the ball 0.4-2.6 mm deep and threw it
// off at 0.5-0.8 m/s along every line tried (docs/physics.md).
TEST(ChartBoundary, FacesASmoothSphereMeshCurvesRoundToAreNoSurfaceAcrossACrease) {
  const Meshed sphere(mesh::sphere(0.001, 128, 64, 0.02));
  for (const Eigen::Vector3d& line : {Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(1, 1, 0), Eigen::Vector3d(1, 1, 1),
                                      Eigen::Vector3d(1, -2, 0.5), Eigen::Vector3d(-0.3, 0.8, 1)}) {
    const Eigen::Vector3d u = line.normalized();
    const ChartBoundary boundary = boundaryUnder(sphere, (0.001 + kObjectRadius - 0.5e-3) * u);
    std::printf("[measured] 1 cm ball on a 1 mm sphere mesh along (%.2f, %.2f, %.2f): %zu edges cut its chart, %zu "
                "surfaces across a crease\n",
                u.x(), u.y(), u.z(), boundary.count, boundary.surface_count);
    // The faces past 60 degrees are there, and still cut the chart (where their planes meet it,
    // 0.58 mm from the foot, the sphere has fallen away below the ball's reach)...
    EXPECT_GT(boundary.count, 0u) << u.transpose();
    // ...but none is a surface of its own: the sphere runs on from them, nearer the ball, to its foot.
    EXPECT_EQ(boundary.surface_count, 0u) << u.transpose();
  }
}

// A slab's top meets its side at a hard edge: an object over the top near the edge, or past it,
// still meets the face across it as a surface across the crease, the nearest points of both on
// the edge itself (past the edge the chart may lie on either face; its foot is on the edge).
TEST(ChartBoundary, ASlabsFacesAcrossItsHardEdgeAreSurfacesAcrossACrease) {
  const Meshed slab(mesh::box(Eigen::Vector3d(0.1, 0.1, 0.02), 0.01, 0.02));  // its top at z = 0.01, edge at x = 0.05
  for (const double x : {0.047, 0.052}) {
    Eigen::Vector3d chart_normal;
    const ChartBoundary boundary = boundaryUnder(slab, Eigen::Vector3d(x, 0.0, 0.01 + 0.008), &chart_normal);
    ASSERT_EQ(boundary.surface_count, 1u) << "centre at x = " << x;
    const Eigen::Vector3d across = mesh::faceNormal(slab.generated.mesh, boundary.surfaces[0].nearest_triangle);
    EXPECT_NEAR(across.dot(chart_normal), 0.0, 1e-9) << "centre at x = " << x;
    EXPECT_NEAR(std::fabs(across.x() + across.z()), 1.0, 1e-9) << "the top or the side; centre at x = " << x;
  }
}

}  // namespace
}  // namespace thx::phys::test::test_chart_boundary
