// Normal-map mode on a uniformly tilted normal map: the analytic cases of docs/design.md §6.
// A ball rolling on a slope of angle θ that it "feels" only through the normal accelerates
// horizontally at a = 5/7 g tanθ (rolling) or g tanθ (frictionless): the flat plane holds the
// ball's height, the sampled normal tilts the push (Eq. 1, Eq. 2).
#include <gtest/gtest.h>

#include <cstdio>

#include "clients/physics/bullet_convert.hpp"
#include "physics_fixtures.hpp"

namespace thx::phys::test::test_normal_map_rolling {
namespace {

constexpr double kRadius = 0.01, kMass = 0.05, kDt = 1e-3;

struct Rolled {
  double accel = 0.0;       // horizontal, from the velocity change between t1 and t2
  double omega_r = 0.0;     // |ω| r at t2
  double v = 0.0;           // |v| at t2
  double z_error = 0.0;     // max |z - r| over the run
  double v_max = 0.0;       // max |v| over the run
  double lateral_y = 0.0;   // |y| at t2
};

// Ball released at rest; a measured between t1 (after the contact settles) and t2.
Rolled rollBall(double angle_deg, double friction, bool plane_first, double dt = kDt, double t1 = 0.1,
                double t2 = 0.5) {
  SurfaceHolder s = holdSurface(tiltedMap(angle_deg, 64, 0.2), 0.2, false);
  PhysicsWorld w;
  btRigidBody* ball = nullptr;
  // Bullet multiplies the two bodies' frictions: the plane takes 1 so the ball's is the pair's.
  const BodyMaterial plane{1.0, 0.0, 0.0}, m{friction, 0.0, 0.0};
  if (plane_first) w.addNormalMapPlane(s.surface, plane);
  ball = &w.addSphere(kRadius, kMass, at(0, 0, kRadius), m);
  if (!plane_first) w.addNormalMapPlane(s.surface, plane);
  Rolled r;
  double v1 = 0.0;
  const int n1 = int(std::lround(t1 / dt)), n2 = int(std::lround(t2 / dt));
  for (int k = 1; k <= n2; ++k) {
    w.step(dt);
    r.z_error = std::max(r.z_error, std::fabs(positionOf(*ball).z() - kRadius));
    r.v_max = std::max(r.v_max, velocityOf(*ball).norm());
    if (k == n1) v1 = velocityOf(*ball).x();
  }
  r.v = velocityOf(*ball).x();
  r.accel = (r.v - v1) / (double(n2 - n1) * dt);
  r.omega_r = angularVelocityOf(*ball).norm() * kRadius;
  r.lateral_y = std::fabs(positionOf(*ball).y());
  return r;
}

class TiltedNormalMap : public ::testing::TestWithParam<bool> {};

TEST_P(TiltedNormalMap, BallRollsAtFiveSeventhsGTanTheta) {
  for (double angle : {2.0, 5.0, 15.0}) {
    const Rolled r = rollBall(angle, 0.5, GetParam());
    const double expected = 5.0 / 7.0 * kG * std::tan(deg(angle));
    SCOPED_TRACE(::testing::Message() << "angle " << angle << " deg: a = " << r.accel << ", expected " << expected);
    EXPECT_NEAR(r.accel, expected, 0.01 * expected);
    // No slip on the virtual slope: the contact moves at v·t = v cosθ along the slope's tangent t.
    EXPECT_NEAR(r.omega_r, r.v * std::cos(deg(angle)), 0.01 * r.v) << "the ball rolls instead of sliding";
    EXPECT_LT(r.lateral_y, 1e-6) << "no sideways drift on a slope along x";
    // Without hold_height the ball would sink by v sinθ dt / erp (1.2 mm at 15°, 0.94 m/s).
    std::printf("[measured] %g deg: a = %.5f (expected %.5f), max |z - r| = %.3g m\n", angle, r.accel, expected,
                r.z_error);
    EXPECT_LT(r.z_error, 5e-5) << "the flat plane keeps the ball's height";
  }
}

TEST_P(TiltedNormalMap, FrictionlessBallSlidesAtGTanTheta) {
  for (double angle : {2.0, 5.0, 15.0}) {
    const Rolled r = rollBall(angle, 0.0, GetParam());
    const double expected = kG * std::tan(deg(angle));
    SCOPED_TRACE(::testing::Message() << "angle " << angle << " deg: a = " << r.accel << ", expected " << expected);
    EXPECT_NEAR(r.accel, expected, 0.01 * expected);
    EXPECT_LT(r.omega_r, 1e-3 * r.v) << "no friction, no spin";
  }
}

INSTANTIATE_TEST_SUITE_P(InsertionOrder, TiltedNormalMap, ::testing::Values(true, false),
                         [](const auto& p) { return p.param ? "PlaneFirst" : "BallFirst"; });

// A box changes only its normals (no Eq. 2): frictionless it slides at g tanθ.
// (With Coulomb friction: g (tanθ - μ) / (1 + μ tanθ), in test_box_friction.cpp.)
TEST(TiltedNormalMapBox, FrictionlessBoxSlidesAtGTanTheta) {
  const double angle = 10.0, th = std::tan(deg(angle));
  SurfaceHolder s = holdSurface(tiltedMap(angle, 64, 0.2), 0.2, false);
  PhysicsWorld w;
  w.addNormalMapPlane(s.surface, {1.0, 0.0, 0.0});
  const double half = 0.01;
  btRigidBody& box = w.addBox({half, half, half}, 0.05, at(0, 0, half), {0.0, 0.0, 0.0});
  double v1 = 0.0;
  for (int k = 1; k <= 500; ++k) {
    w.step(kDt);
    if (k == 100) v1 = velocityOf(box).x();
  }
  const double accel = (velocityOf(box).x() - v1) / 0.4;
  EXPECT_NEAR(accel, kG * th, 0.01 * kG * th);
  const Eigen::Vector3d up = toEigen(box.getWorldTransform().getBasis().getColumn(2));
  EXPECT_GT(up.z(), std::cos(deg(1.0))) << "the box slides flat, it does not tip";
  EXPECT_NEAR(positionOf(box).z(), half, 2e-4) << "the flat plane holds its height";
}

// The plane need not be horizontal in the world: rotate plane and gravity together and the
// motion, expressed in the plane frame, is the same.
TEST(TiltedNormalMapFrames, RotatedPlaneGivesTheSameRolling) {
  const double angle = 5.0;
  Eigen::Isometry3d plane_to_world = Eigen::Isometry3d::Identity();
  plane_to_world.linear() = Eigen::AngleAxisd(deg(90.0), Eigen::Vector3d::UnitX()).toRotationMatrix() *
                            Eigen::AngleAxisd(deg(30.0), Eigen::Vector3d::UnitZ()).toRotationMatrix();
  plane_to_world.translation() = Eigen::Vector3d(0.3, -0.2, 0.1);
  SurfaceHolder s = holdSurface(tiltedMap(angle, 64, 0.2), 0.2, false, tex::Address::Wrap, plane_to_world);
  WorldOptions o;
  o.gravity_m_per_s2 = plane_to_world.linear() * Eigen::Vector3d(0, 0, -kG);
  PhysicsWorld w(o);
  w.addNormalMapPlane(s.surface, {0.5, 0.0, 0.0});
  btRigidBody& ball = w.addSphere(kRadius, kMass, plane_to_world * at(0, 0, kRadius), {0.5, 0.0, 0.0});
  double v1 = 0.0;
  for (int k = 1; k <= 500; ++k) {
    w.step(kDt);
    if (k == 100) v1 = (plane_to_world.linear().transpose() * velocityOf(ball)).x();
  }
  const Eigen::Vector3d v_local = plane_to_world.linear().transpose() * velocityOf(ball);
  const double accel = (v_local.x() - v1) / 0.4;
  const double expected = 5.0 / 7.0 * kG * std::tan(deg(angle));
  EXPECT_NEAR(accel, expected, 0.01 * expected);
  EXPECT_LT(std::fabs(v_local.y()), 1e-3 * std::fabs(v_local.x()));
}

}  // namespace
}  // namespace thx::phys::test::test_normal_map_rolling
