// A ball's further relief contacts that are still open while it moves onto them are left to the
// next step (speculative_contacts.hpp): the rule. What it is for, a ball on the relief plane
// slowing at the troughs of sine ridges as a rigid ball does, is in test_relief_mesh_ridges.cpp.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "clients/physics/speculative_contacts.hpp"

namespace thx::phys::test::test_speculative_contacts {
namespace {

TEST(SpeculativeContacts, TheApproachIsThePointsVelocityIntoTheSurfaceRollingIncluded) {
  BodyMotion ball;
  ball.centre = Eigen::Vector3d(0.0, 0.0, 0.01);
  ball.linear = Eigen::Vector3d(0.2, 0.0, 0.0);
  ball.angular = Eigen::Vector3d(0.0, 20.0, 0.0);  // rolling along +x without slipping, r = 1 cm
  // The bottom point does not move: no approach to the floor under it.
  EXPECT_NEAR(approachSpeed(ball, {0.0, 0.0, 0.0}, Eigen::Vector3d::UnitZ()), 0.0, 1e-12);
  // A wall ahead, facing -x, at the ball's equator: the point there moves onto it at v (its
  // rolling adds nothing along x at the height of the centre).
  EXPECT_NEAR(approachSpeed(ball, {0.01, 0.0, 0.01}, -Eigen::Vector3d::UnitX()), 0.2, 1e-12);
  // A wall behind: moving away from it.
  EXPECT_NEAR(approachSpeed(ball, {-0.01, 0.0, 0.01}, Eigen::Vector3d::UnitX()), -0.2, 1e-12);
  // A far flank ahead, tilted 45 degrees: the point at the flank's foot on the ball, q = c - r n.
  const Eigen::Vector3d n = Eigen::Vector3d(-1.0, 0.0, 1.0).normalized();
  const Eigen::Vector3d q = ball.centre - 0.01 * n;
  const Eigen::Vector3d v_q = ball.linear + ball.angular.cross(q - ball.centre);
  EXPECT_NEAR(approachSpeed(ball, q, n), -v_q.dot(n), 1e-12);
  EXPECT_GT(approachSpeed(ball, q, n), 0.0);
}

TEST(SpeculativeContacts, AnOpenPointIsLeftOutOnlyWhileTheBallMovesOntoItFast) {
  // Touching or overlapping: always kept, however fast.
  EXPECT_TRUE(keepFurtherContact(0.0, 1.0));
  EXPECT_TRUE(keepFurtherContact(-1e-4, 1.0));
  // Open: kept at rest, creeping, or moving away; left out above the approach speed.
  EXPECT_TRUE(keepFurtherContact(1e-4, 0.0));
  EXPECT_TRUE(keepFurtherContact(1e-4, -0.5));
  EXPECT_TRUE(keepFurtherContact(1e-4, kSpeculativeApproachSpeed));
  EXPECT_FALSE(keepFurtherContact(1e-4, 2.0 * kSpeculativeApproachSpeed));
  EXPECT_FALSE(keepFurtherContact(1e-9, 0.5));
}

}  // namespace
}  // namespace thx::phys::test::test_speculative_contacts
