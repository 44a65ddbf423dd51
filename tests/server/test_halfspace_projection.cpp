// The proxy's constraint solver: exact projections, creases, corners, and continuity.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>
#include <random>

#include "server/halfspace_projection.hpp"

namespace test_halfspace_projection {

using namespace thx::srv;

namespace {
Halfspace plane(Eigen::Vector3d n, double d) { return {n.normalized(), d}; }
}  // namespace

TEST(HalfspaceProjection, InsideStaysPut) {
  std::array<Halfspace, kMaxHalfspaces> h{plane({0, 0, 1}, 0.0)};
  const Projection p = projectOntoHalfspaces({0.1, 0.2, 0.001}, h, 1);
  EXPECT_TRUE(p.inside);
  EXPECT_EQ(p.x, Eigen::Vector3d(0.1, 0.2, 0.001));
}

TEST(HalfspaceProjection, SinglePlaneIsOrthogonalProjection) {
  const Eigen::Vector3d n = Eigen::Vector3d(0.3, -0.2, 1.0).normalized();
  std::array<Halfspace, kMaxHalfspaces> h{Halfspace{n, 0.002}};
  const Eigen::Vector3d tip(0.01, 0.02, -0.003);
  const Projection p = projectOntoHalfspaces(tip, h, 1);
  ASSERT_TRUE(p.solved);
  EXPECT_FALSE(p.inside);
  EXPECT_EQ(p.active_mask, 1u);
  EXPECT_NEAR(n.dot(p.x), 0.002, 1e-15);
  EXPECT_LT((p.x - tip).cross(n).norm(), 1e-15);  // moved along the normal only
}

TEST(HalfspaceProjection, VValleyFloorHoldsBothWalls) {
  // Walls at 60 deg from the plane meeting at x = 0, z = -0.002.
  const double a = 60.0 * std::numbers::pi / 180.0;
  const Eigen::Vector3d nl(std::sin(a), 0, std::cos(a)), nr(-std::sin(a), 0, std::cos(a));
  const Eigen::Vector3d floor(0, 0, -0.002);
  std::array<Halfspace, kMaxHalfspaces> h{Halfspace{nl, nl.dot(floor)}, Halfspace{nr, nr.dot(floor)}};
  for (double x : {-1e-4, 0.0, 2e-4}) {
    const Projection p = projectOntoHalfspaces({x, 0.005, -0.004}, h, 2);
    ASSERT_TRUE(p.solved);
    EXPECT_EQ(p.active_mask, 3u) << x;  // the crease line
    EXPECT_NEAR(p.x.x(), 0.0, 1e-15);
    EXPECT_NEAR(p.x.z(), -0.002, 1e-15);
    EXPECT_NEAR(p.x.y(), 0.005, 1e-15);
  }
}

TEST(HalfspaceProjection, CornerOfThreePlanes) {
  std::array<Halfspace, kMaxHalfspaces> h{plane({1, 0, 0.2}, 0.0), plane({0, 1, 0.2}, 0.0), plane({-1, -1, 0.3}, 0.0)};
  const Projection p = projectOntoHalfspaces({0.0, 0.0, -0.01}, h, 3);
  ASSERT_TRUE(p.solved);
  EXPECT_EQ(p.active_mask, 7u);
  EXPECT_LT(p.x.norm(), 1e-12);
}

TEST(HalfspaceProjection, IsOneLipschitzSoForcesAreContinuous) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 300; ++trial) {
    std::array<Halfspace, kMaxHalfspaces> h{};
    const int count = 1 + trial % 4;
    for (int i = 0; i < count; ++i) {
      // Upward-facing planes through points near the origin (like surface planes).
      // Each draw its own statement, in g++'s right-to-left order of a call's arguments, so that
      // every compiler draws these numbers (the order of a call's arguments is unspecified).
      const double ny = u(rng), nx = u(rng);
      const Eigen::Vector3d n = Eigen::Vector3d(0.8 * nx, 0.8 * ny, 1.0).normalized();
      h[std::size_t(i)] = {n, 0.001 * u(rng)};
    }
    for (int k = 0; k < 20; ++k) {
      const double az = u(rng), ay = u(rng), ax = u(rng);
      const Eigen::Vector3d a = 0.003 * Eigen::Vector3d(ax, ay, az);
      const double dz = u(rng), dy = u(rng), dx = u(rng);
      const Eigen::Vector3d b = a + Eigen::Vector3d(dx, dy, dz) * 1e-4;
      const Projection pa = projectOntoHalfspaces(a, h, count), pb = projectOntoHalfspaces(b, h, count);
      ASSERT_TRUE(pa.solved && pb.solved);
      EXPECT_LE((pa.x - pb.x).norm(), (a - b).norm() * (1 + 1e-9) + 1e-12);
      for (int i = 0; i < count; ++i) EXPECT_GE(h[std::size_t(i)].n.dot(pa.x), h[std::size_t(i)].d - 1e-11);
    }
  }
}

}  // namespace test_halfspace_projection
