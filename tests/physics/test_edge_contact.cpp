// A rod's side on a chart's convex edge takes the rod's normal (clients/physics/edge_contact.hpp):
// the rule on contacts built by hand, in the chart's frame. The chart holds x < 0 (its edge at
// x = 0, the face across it facing +x); the rod is 3 mm in radius, 1 cm from its centre to each
// end, lying along x across the edge, tipped down over it or level.
#include <gtest/gtest.h>

#include <cmath>

#include "clients/physics/edge_contact.hpp"

namespace thx::phys::test::test_edge_contact {
namespace {

constexpr double kRadius = 0.003, kHalf = 0.01, kBand = 0.0005;

ChartBoundary edgeAtOrigin(bool convex) {
  ChartBoundary b;
  b.count = 1;
  b.edges[0].normal = Eigen::Vector2d::UnitX();
  b.edges[0].offset = 0.0;
  b.edges[0].across_normal = Eigen::Vector3d::UnitX();
  b.edges[0].across_offset = 0.0;
  b.edges[0].convex = convex;
  return b;
}

// A rod whose axis runs along x tipped down over the edge by `tilt` (rad), its side resting on
// the edge's line (x = 0, z = 0): its axis r from that line, its centre `past` along the axis.
Underside rodOverTheEdge(Underside::Kind kind, double tilt, double past) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  const Eigen::Vector3d axis(std::cos(tilt), 0.0, -std::sin(tilt)), up(std::sin(tilt), 0.0, std::cos(tilt));
  pose.linear() = Eigen::AngleAxisd(0.5 * M_PI + tilt, Eigen::Vector3d::UnitY()).toRotationMatrix();  // object z onto axis
  pose.translation() = past * axis + kRadius * up;
  return kind == Underside::Kind::Cylinder ? Underside::cylinder(pose, kRadius, kHalf) : Underside::capsule(pose, kRadius, kHalf);
}

ChosenReliefContacts oneContactAt(const Eigen::Vector3d& p) {
  ChosenReliefContacts chosen;
  chosen.count = 1;
  chosen.contacts[0].p_surface = p;
  chosen.contacts[0].n_local = Eigen::Vector3d::UnitZ();
  return chosen;
}

TEST(EdgeContact, ARodTippedOverAConvexEdgeIsPushedAlongItsOwnNormalThere) {
  for (const Underside::Kind kind : {Underside::Kind::Cylinder, Underside::Kind::Capsule}) {
    const double tilt = 0.3;
    const Underside rod = rodOverTheEdge(kind, tilt, 0.002);
    ChosenReliefContacts chosen = oneContactAt({-1e-4, 0.0, 0.0});
    rodNormalsAtConvexEdges(rod, edgeAtOrigin(true), kBand, chosen);
    // From the contact square to the axis: the axis's "up", leaning out over the edge by the tilt.
    const Eigen::Vector3d expected(std::sin(tilt), 0.0, std::cos(tilt));
    EXPECT_LT((chosen.contacts[0].n_local - expected).norm(), 0.02) << chosen.contacts[0].n_local.transpose();
  }
}

TEST(EdgeContact, ContactsAwayFromTheEdgeOrOnAConcaveOneKeepTheReliefsNormal) {
  const Underside rod = rodOverTheEdge(Underside::Kind::Cylinder, 0.3, 0.002);
  ChosenReliefContacts far = oneContactAt({-2e-3, 0.0, 0.0});  // four bands in from the edge
  rodNormalsAtConvexEdges(rod, edgeAtOrigin(true), kBand, far);
  EXPECT_EQ(far.contacts[0].n_local, Eigen::Vector3d::UnitZ());
  ChosenReliefContacts past = oneContactAt({1e-4, 0.0, 0.0});  // past the edge: not the chart's
  rodNormalsAtConvexEdges(rod, edgeAtOrigin(true), kBand, past);
  EXPECT_EQ(past.contacts[0].n_local, Eigen::Vector3d::UnitZ());
  ChosenReliefContacts concave = oneContactAt({-1e-4, 0.0, 0.0});  // a room's floor by its wall
  rodNormalsAtConvexEdges(rod, edgeAtOrigin(false), kBand, concave);
  EXPECT_EQ(concave.contacts[0].n_local, Eigen::Vector3d::UnitZ());
}

TEST(EdgeContact, ALevelRodAndACylindersEndFaceKeepTheReliefsNormal) {
  // Level across the edge (a rail under a block's edge): its normal leans by nothing.
  const Underside level = rodOverTheEdge(Underside::Kind::Cylinder, 0.0, 0.0);
  ChosenReliefContacts on_level = oneContactAt({-1e-4, 0.0, 0.0});
  rodNormalsAtConvexEdges(level, edgeAtOrigin(true), kBand, on_level);
  EXPECT_EQ(on_level.contacts[0].n_local, Eigen::Vector3d::UnitZ());
  // A cylinder tipped over the edge with its end face's rim on it (its centre a half length and
  // more past the edge): the rim is not its side.
  const Underside rim = rodOverTheEdge(Underside::Kind::Cylinder, 0.3, kHalf + 1e-3);
  ChosenReliefContacts on_rim = oneContactAt({-1e-4, 0.0, 0.0});
  rodNormalsAtConvexEdges(rim, edgeAtOrigin(true), kBand, on_rim);
  EXPECT_EQ(on_rim.contacts[0].n_local, Eigen::Vector3d::UnitZ());
}

}  // namespace
}  // namespace thx::phys::test::test_edge_contact
