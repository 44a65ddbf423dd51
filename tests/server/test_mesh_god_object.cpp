// The mesh god object: exact plane force on a flat mesh, the constrained proxy in a V valley (two
// planes) and a corner (three), no pop-through across edges and vertices, no allocation per tick
// (its own and, at the end, the textured mesh renderer's built on it).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>
#include <random>

#include "meshes/mesh_generators.hpp"
#include "server/mesh_god_object.hpp"
#include "server/textured_mesh_renderer.hpp"
#include "tests/server/mesh_fixtures.hpp"
#include "tests/support/allocation_counter.hpp"

namespace test_mesh_god_object {

using namespace thx;
using srv::MeshGodObject;

namespace {

constexpr double kK = 600.0;
constexpr double kStep = 2e-5;  // m per tick: 20 mm/s at 1 kHz

srv::RendererConfig config(double damping = 0.0) {
  srv::RendererConfig c;
  c.stiffness_n_per_m = kK;
  c.damping_ns_per_m = damping;
  return c;
}

// Descends vertically from z_start to the tip, then holds there `hold` ticks; the last output.
srv::RenderOutput press(MeshGodObject& r, const Eigen::Vector3d& tip, double z_start, int hold = 5) {
  r.reset();
  for (double z = z_start; z > tip.z(); z -= kStep) r.render({tip.x(), tip.y(), z}, Eigen::Vector3d::Zero());
  srv::RenderOutput out;
  for (int k = 0; k < hold; ++k) out = r.render(tip, Eigen::Vector3d::Zero());
  return out;
}

// Walls z = tan(a) |x| meeting in a floor along y at x = 0 (a grid line for even n).
srv::TriangleMesh valley(double angle_deg, int n, double half) {
  const double slope = std::tan(angle_deg * std::numbers::pi / 180.0);
  return test::gridMesh(n, half, [slope](double x, double) { return slope * std::fabs(x); });
}

}  // namespace

TEST(MeshGodObject, FlatMeshGivesThePlaneForce) {
  const srv::TriangleMesh mesh = test::gridMesh(8, 0.01, [](double, double) { return -0.001; });
  const srv::TriangleBvh bvh(mesh);
  tex::PlaneMapping mapping;
  MeshGodObject r(bvh, mapping, config());
  // In a triangle, on an edge, on the diagonal, on a vertex.
  for (const Eigen::Vector2d& xy : {Eigen::Vector2d(0.0013, -0.0041), Eigen::Vector2d(0.0025, 0.0011),
                                   Eigen::Vector2d(0.0031, 0.0031), Eigen::Vector2d(0.0025, -0.005)}) {
    for (double depth : {0.25e-3, 1e-3, 2e-3}) {
      const srv::RenderOutput out = press(r, {xy.x(), xy.y(), -0.001 - depth}, 0.0);
      ASSERT_TRUE(out.in_contact);
      EXPECT_NEAR(out.force_world.x(), 0.0, 1e-12);
      EXPECT_NEAR(out.force_world.y(), 0.0, 1e-12);
      EXPECT_NEAR(out.force_world.z(), kK * depth, kK * 2 * MeshGodObject::kStandoffM);
      EXPECT_NEAR(out.proxy_world.z(), -0.001, 2 * MeshGodObject::kStandoffM);
      EXPECT_EQ(out.num_planes, 1);
    }
  }
  // Lifting the tip off: no force, the proxy is the tip.
  const srv::RenderOutput off = r.render({0.001, 0.001, 0.0005}, Eigen::Vector3d::Zero());
  EXPECT_FALSE(off.in_contact);
  EXPECT_EQ(off.force_world, Eigen::Vector3d::Zero());
  EXPECT_EQ(off.proxy_world, Eigen::Vector3d(0.001, 0.001, 0.0005));
}

TEST(MeshGodObject, PlacedMeshAndDampingAsTheTextureRenderers) {
  const srv::TriangleMesh mesh = test::gridMesh(4, 0.01, [](double, double) { return 0.0; });
  const srv::TriangleBvh bvh(mesh);
  tex::PlaneMapping mapping;
  mapping.plane_to_world = Eigen::Translation3d(0.1, -0.2, 0.05) * Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 0.5).normalized());
  MeshGodObject r(bvh, mapping, config(2.0));
  const Eigen::Vector3d n = mapping.plane_to_world.linear().col(2);
  const Eigen::Vector3d tip = mapping.plane_to_world * Eigen::Vector3d(0.002, 0.003, -0.001);
  r.render(mapping.plane_to_world * Eigen::Vector3d(0.002, 0.003, 0.001), Eigen::Vector3d::Zero());
  // Moving into the surface at 0.05 m/s: spring plus damper, along the plane's normal.
  const srv::RenderOutput in = r.render(tip, -0.05 * n);
  EXPECT_LT((in.force_world - (kK * 0.001 + 2.0 * 0.05) * n).norm(), 1e-6);
  // Moving out fast: the damper would pull the pen in; the force is clamped at zero instead.
  const srv::RenderOutput out = r.render(tip, 1.0 * n);
  EXPECT_EQ(out.force_world, Eigen::Vector3d::Zero());
  EXPECT_TRUE(out.in_contact);
  ASSERT_EQ(out.num_planes, 1);
  EXPECT_LT((out.planes[0].n_world - n).norm(), 1e-12);
  EXPECT_NEAR(out.planes[0].n_world.dot(out.proxy_world) - out.planes[0].d_m, 0.0, 1e-12);
}

TEST(MeshGodObject, VValleyFloorHoldsBothWalls) {
  const srv::TriangleMesh mesh = valley(60.0, 16, 0.004);
  const srv::TriangleBvh bvh(mesh);
  MeshGodObject r(bvh, tex::PlaneMapping{}, config());
  // Deep under the floor, off-centre: both walls' multipliers are positive, so the proxy is the
  // floor point above the tip (see HalfspaceProjection.VValleyFloorHoldsBothWalls).
  for (const Eigen::Vector3d& tip : {Eigen::Vector3d(0.0003, 0.0011, -0.004), Eigen::Vector3d(-0.0002, -0.0005, -0.002),
                                    Eigen::Vector3d(0.0, 0.0005, -0.001)}) {
    const srv::RenderOutput out = press(r, tip, 0.01);
    EXPECT_LT((out.proxy_world - Eigen::Vector3d(0, tip.y(), 0)).norm(), 1e-8) << out.proxy_world.transpose();
    EXPECT_LT((out.force_world - kK * (Eigen::Vector3d(0, tip.y(), 0) - tip)).norm(), 1e-5);
    EXPECT_EQ(out.num_planes, 2);
  }
  // Shallow, near one wall: only that wall holds it; the proxy is the tip's projection onto it.
  const double a = 60.0 * std::numbers::pi / 180.0;
  const Eigen::Vector3d n_right(-std::sin(a), 0, std::cos(a));  // the wall x > 0
  const Eigen::Vector3d tip(0.002, 0.0, std::tan(a) * 0.002 - 0.0002);
  const srv::RenderOutput out = press(r, tip, 0.01);
  const Eigen::Vector3d expected = tip - n_right.dot(tip) * n_right;
  EXPECT_LT((out.proxy_world - expected).norm(), 1e-8);
  EXPECT_EQ(out.num_planes, 1);
}

TEST(MeshGodObject, CornerHoldsThreePlanes) {
  // z = max_i s (x, y) . u_i, u_i at 0, 120, 240 degrees: three planes meeting at the origin,
  // meshed as a fan whose spokes (every 60 degrees) contain the three creases.
  const double s = 1.0, radius = 0.01;
  srv::TriangleMesh mesh;
  const auto height = [&](double x, double y) {
    double h = -1e9;
    for (int i = 0; i < 3; ++i) {
      const double th = 2 * std::numbers::pi * i / 3;
      h = std::max(h, s * (x * std::cos(th) + y * std::sin(th)));
    }
    return h;
  };
  mesh.vertices.emplace_back(0, 0, 0);
  for (int k = 0; k < 6; ++k) {
    const double th = std::numbers::pi * k / 3;
    const double x = radius * std::cos(th), y = radius * std::sin(th);
    mesh.vertices.emplace_back(x, y, height(x, y));
  }
  for (std::uint32_t k = 0; k < 6; ++k) mesh.triangles.push_back({0, 1 + k, 1 + (k + 1) % 6});
  const srv::TriangleBvh bvh(mesh);
  MeshGodObject r(bvh, tex::PlaneMapping{}, config());
  for (const Eigen::Vector3d& tip : {Eigen::Vector3d(0.0002, 0.0001, -0.005), Eigen::Vector3d(-0.0003, 0.0002, -0.003)}) {
    const srv::RenderOutput out = press(r, tip, 0.02);
    EXPECT_LT(out.proxy_world.norm(), 1e-8) << out.proxy_world.transpose();
    EXPECT_LT((out.force_world + kK * tip).norm(), 1e-5);
    EXPECT_EQ(out.num_planes, 3);
  }
  // Above a crease between two of the planes, shallow: the crease line holds it (two planes).
  const Eigen::Vector3d crease_dir(std::cos(std::numbers::pi / 3), std::sin(std::numbers::pi / 3), 0.5);
  const Eigen::Vector3d on_crease = 0.004 * crease_dir;  // height there: s * 0.004 * cos(60°) = 0.002
  const Eigen::Vector3d tip = on_crease - Eigen::Vector3d(0, 0, 0.0005);
  const srv::RenderOutput out = press(r, tip, 0.02);
  const Eigen::Vector3d d = crease_dir.normalized();
  const Eigen::Vector3d expected = d.dot(tip) * d;  // the tip's projection onto the crease line
  EXPECT_LT((out.proxy_world - expected).norm(), 1e-8);
  EXPECT_EQ(out.num_planes, 2);
}

TEST(MeshGodObject, NoPopThroughAcrossEdgesAndVertices) {
  // A rough mesh (random heights, peaks and pits one cell apart, in a rim) and strokes at depth along grid
  // lines (through every vertex), along diagonals and at odd angles: the proxy stays on or above
  // the surface at every tick, and the pen always feels it.
  const int n = 12;
  const double half = 0.006;
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-0.0015, 0.0);
  std::vector<double> heights(std::size_t((n + 1) * (n + 1)));
  for (double& h : heights) h = u(rng);
  const auto at = [&](double x, double y) {
    const int c = int(std::lround((x + half) / (2 * half) * n)), r = int(std::lround((y + half) / (2 * half) * n));
    // A high rim all round: a deep tip pulls the proxy downhill, and an open mesh's border would
    // let it slide off the edge (correctly: nothing is there) instead of testing the inside.
    if (r == 0 || c == 0 || r == n || c == n) return 0.004;
    return heights[std::size_t(r * (n + 1) + c)];
  };
  const srv::TriangleMesh mesh = test::gridMesh(n, half, at);
  const srv::TriangleBvh bvh(mesh);
  MeshGodObject r(bvh, tex::PlaneMapping{}, config());
  const double cell = 2 * half / n;
  struct Stroke {
    Eigen::Vector2d a, b;
  };
  const Stroke strokes[] = {
      {{-half + cell, -half + 2 * cell}, {half - cell, -half + 2 * cell}},  // along a grid line
      {{-half + 2 * cell, -half + cell}, {-half + 2 * cell, half - cell}},  // along a column
      {{-half + cell, -half + cell}, {half - cell, half - cell}},            // the diagonals' line
      {{-half + cell, half - cell}, {half - cell, -half + cell}},           // against the diagonals
      {{-half + cell, -0.0011}, {half - cell, 0.0023}},                     // an odd angle
  };
  long ticks = 0, contact_ticks = 0;
  for (const Stroke& s : strokes) {
    for (double depth : {0.0002, 0.003}) {
      r.reset();
      const auto surf = [&](const Eigen::Vector2d& p) { return test::gridHeight(mesh, n, half, p.x(), p.y()); };
      r.render({s.a.x(), s.a.y(), 0.002}, Eigen::Vector3d::Zero());
      for (double z = 0.002; z > surf(s.a) - depth; z -= kStep) r.render({s.a.x(), s.a.y(), z}, Eigen::Vector3d::Zero());
      const int steps = int((s.b - s.a).norm() / (2.5 * kStep));  // 50 mm/s
      for (int k = 0; k <= steps; ++k) {
        const Eigen::Vector2d p = s.a + (s.b - s.a) * (double(k) / steps);
        const srv::RenderOutput out = r.render({p.x(), p.y(), surf(p) - depth}, Eigen::Vector3d::Zero());
        const Eigen::Vector3d q = out.proxy_world;
        ++ticks;
        contact_ticks += out.in_contact ? 1 : 0;
        ASSERT_GE(q.z(), test::gridHeight(mesh, n, half, q.x(), q.y()) - 1e-12)
            << "proxy below the surface at tick " << k << " of the stroke " << s.a.transpose() << " -> "
            << s.b.transpose() << ", depth " << depth;
      }
    }
  }
  EXPECT_EQ(contact_ticks, ticks);  // the tip is below the surface throughout: always a force
}

TEST(MeshGodObject, NoAllocationPerTick) {
  const srv::TriangleMesh mesh = valley(45.0, 16, 0.004);
  const srv::TriangleBvh bvh(mesh);
  MeshGodObject r(bvh, tex::PlaneMapping{}, config(1.0));
  r.render({0.001, 0.0, 0.01}, Eigen::Vector3d::Zero());
  const long before = test::g_allocations.load();
  for (int k = 0; k < 2000; ++k) {
    // Down into the valley, then across the floor and up the far wall.
    const double t = k / 2000.0;
    const Eigen::Vector3d tip(0.003 * std::cos(6 * t), 0.003 * std::sin(3 * t), 0.004 - 0.006 * t);
    r.render(tip, Eigen::Vector3d(0, 0, -0.02));
  }
  r.reset();
  EXPECT_EQ(test::g_allocations.load() - before, 0);
}

TEST(TexturedMeshRenderer, NoAllocationPerTick) {
  // The textured renderer on a relief-mapped sphere: strokes across edges, seams and the pole.
  const mesh::GeneratedMesh g = mesh::sphere(0.03, 24, 12, 0.01);
  const srv::TriangleBvh bvh(g.mesh.positions, g.mesh.triangles);
  tex::TextureMap map(16, 16, tex::Representation::Relief, 2e-4);
  for (int j = 0; j < 16; ++j) {
    for (int i = 0; i < 16; ++i) {
      map.setNormal(i, j, Eigen::Vector3f(0.1f * float(i % 3), -0.05f * float(j % 2), 1.0f));
      map.setDepth(i, j, 1e-5 * ((i + j) % 7));
    }
  }
  srv::TexturedMeshRenderer r(g.mesh, bvh, {&map, {}, true}, Eigen::Isometry3d::Identity(), config(1.0));
  r.render({0.0, 0.0, 0.05}, Eigen::Vector3d::Zero());
  const long before = test::g_allocations.load();
  int contact = 0;
  for (int k = 0; k < 3000; ++k) {
    const double t = k / 3000.0, rho = 0.032 - 0.003 * std::min(1.0, 20 * t);  // from outside to 1 mm deep
    const Eigen::Vector3d dir(std::cos(9 * t) * std::sin(0.2 + 2.8 * t), std::sin(9 * t) * std::sin(0.2 + 2.8 * t),
                              std::cos(0.2 + 2.8 * t));
    contact += r.render(rho * dir, Eigen::Vector3d(0, 0, -0.02)).in_contact ? 1 : 0;
  }
  r.reset();
  EXPECT_EQ(test::g_allocations.load() - before, 0);
  EXPECT_GT(contact, 2000);
}

}  // namespace test_mesh_god_object
