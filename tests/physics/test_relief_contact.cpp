// Relief-map mode: the relief plane shape and its collision algorithms (sphere, box, capsule,
// cylinder) against analytic answers: resting heights, rolling and sliding down a uniformly
// tilted relief, both pair orders.
#include <gtest/gtest.h>

#include <BulletCollision/CollisionShapes/btConeShape.h>

#include "clients/physics/bullet_convert.hpp"
#include "clients/physics/relief_collision.hpp"
#include "physics_fixtures.hpp"

namespace thx::phys::test::test_relief_contact {
namespace {

constexpr double kDt = 1e-3;
const BodyMaterial kPlane{1.0, 0.0, 0.0};  // Bullet multiplies frictions: the object's decides

// The tilted relief of the texture generator. Its depth is 0 at the first texel CENTRE, so the
// plane-local surface is z = -tanθ (x + extent/2 - texel/2). The ramp does not tile: the tests
// stay clear of the wrap seam at x = +-extent/2.
struct TiltedRelief {
  double angle_deg, extent = 0.2;
  int size;
  SurfaceHolder s;
  explicit TiltedRelief(double a, int n = 512)
      : angle_deg(a), size(n), s(holdSurface(tiltedMap(a, n, 0.2), 0.2, true)) {}
  double surfaceZ(double x) const {
    return -std::tan(deg(angle_deg)) * (x + 0.5 * extent - 0.5 * extent / size);
  }
};

// Acceleration along x between t1 and t2 of a body released at rest.
double accelX(PhysicsWorld& w, btRigidBody& body, double t1 = 0.1, double t2 = 0.3) {
  double v1 = 0.0;
  const int n1 = int(std::lround(t1 / kDt)), n2 = int(std::lround(t2 / kDt));
  for (int k = 1; k <= n2; ++k) {
    w.step(kDt);
    if (k == n1) v1 = velocityOf(body).x();
  }
  return (velocityOf(body).x() - v1) / (t2 - t1);
}

class ReliefOrder : public ::testing::TestWithParam<bool> {};

TEST_P(ReliefOrder, BallRollsDownATiltedReliefAtFiveSeventhsGSinTheta) {
  // A real slope: along the slope a = 5/7 g sinθ, so horizontally 5/7 g sinθ cosθ.
  for (double angle : {5.0, 20.0}) {
    TiltedRelief t(angle);
    PhysicsWorld w;
    const double r = 0.01, x0 = -0.08;
    if (GetParam()) w.addReliefPlane(t.s.surface, kPlane);
    btRigidBody& ball = w.addSphere(r, 0.05, at(x0, 0, t.surfaceZ(x0) + r / std::cos(deg(angle))), {0.5, 0, 0});
    if (!GetParam()) w.addReliefPlane(t.s.surface, kPlane);
    const double a = accelX(w, ball);
    const double expected = 5.0 / 7.0 * kG * std::sin(deg(angle)) * std::cos(deg(angle));
    EXPECT_NEAR(a, expected, 0.01 * expected) << "angle " << angle;
    // It stays on the slope: centre at r along the normal above the surface.
    const Eigen::Vector3d p = positionOf(ball);
    EXPECT_NEAR((p.z() - t.surfaceZ(p.x())) * std::cos(deg(angle)), r, 2e-5) << "angle " << angle;
    EXPECT_NEAR(angularVelocityOf(ball).y() * r, velocityOf(ball).norm(), 0.01 * velocityOf(ball).norm())
        << "rolls without slipping";
  }
}

INSTANTIATE_TEST_SUITE_P(PairOrder, ReliefOrder, ::testing::Values(true, false),
                         [](const auto& p) { return p.param ? "PlaneFirst" : "BodyFirst"; });

// Boxes use 128^2 texels (1.6 mm): a 2 cm box's footprint is then ~13^2 texels, which keeps the
// sanitizer build within its time budget; the slope is exact at any resolution.
TEST(ReliefShapes, FrictionlessBoxSlidesAtGSinTheta) {
  const double angle = 10.0;
  TiltedRelief t(angle, 128);
  PhysicsWorld w;
  w.addReliefPlane(t.s.surface, kPlane);
  const double h = 0.01, x0 = -0.05;
  Eigen::Isometry3d pose = at(x0, 0, t.surfaceZ(x0) + h / std::cos(deg(angle)) + 1e-4);
  pose.linear() = Eigen::AngleAxisd(deg(angle), Eigen::Vector3d::UnitY()).toRotationMatrix();  // face on the slope
  btRigidBody& box = w.addBox({h, h, h}, 0.05, pose, {0.0, 0, 0});
  const double a = accelX(w, box);
  const double expected = kG * std::sin(deg(angle)) * std::cos(deg(angle));
  EXPECT_NEAR(a, expected, 0.02 * expected);
  const Eigen::Vector3d up = toEigen(box.getWorldTransform().getBasis().getColumn(2));
  const Eigen::Vector3d slope_normal(std::sin(deg(angle)), 0.0, std::cos(deg(angle)));
  EXPECT_GT(up.dot(slope_normal), std::cos(deg(1.0))) << "slides on its face without tumbling";
}

TEST(ReliefShapes, BoxWithEnoughFrictionStaysOnTheSlope) {
  const double angle = 10.0;  // tan 10° = 0.176 < mu = 0.5
  TiltedRelief t(angle, 128);
  PhysicsWorld w;
  w.addReliefPlane(t.s.surface, kPlane);
  const double h = 0.01, x0 = -0.05;
  Eigen::Isometry3d pose = at(x0, 0, t.surfaceZ(x0) + h / std::cos(deg(angle)));
  pose.linear() = Eigen::AngleAxisd(deg(angle), Eigen::Vector3d::UnitY()).toRotationMatrix();
  btRigidBody& box = w.addBox({h, h, h}, 0.05, pose, {0.5, 0, 0});
  for (int k = 0; k < 100; ++k) w.step(kDt);
  const Eigen::Vector3d p0 = positionOf(box);
  for (int k = 0; k < 400; ++k) w.step(kDt);
  EXPECT_LT((positionOf(box) - p0).norm(), 4e-5) << "static friction holds it (creep over 0.4 s)";
  EXPECT_LT(velocityOf(box).norm(), 1e-3);
}

TEST(ReliefShapes, CylinderOnItsSideRollsWithItsOwnInertia) {
  // A rolling body of inertia I about its axis: along the slope a = g sinθ / (1 + I / (m r^2)).
  const double angle = 8.0, r = 0.008, half = 0.015, mass = 0.05;
  TiltedRelief t(angle, 256);
  PhysicsWorld w;
  w.addReliefPlane(t.s.surface, kPlane);
  const double x0 = -0.05;
  Eigen::Isometry3d pose = at(x0, 0, t.surfaceZ(x0) + r / std::cos(deg(angle)));
  pose.linear() = Eigen::AngleAxisd(deg(90.0), Eigen::Vector3d::UnitX()).toRotationMatrix();  // axis along y
  btRigidBody& cyl = w.addCylinder(r, half, mass, pose, {0.5, 0, 0});
  const double inertia = 1.0 / double(cyl.getInvInertiaDiagLocal().z());  // about the cylinder's own axis
  const double a = accelX(w, cyl);
  const double expected = kG * std::sin(deg(angle)) * std::cos(deg(angle)) / (1.0 + inertia / (mass * r * r));
  EXPECT_NEAR(a, expected, 0.02 * expected);
  const Eigen::Vector3d axis = toEigen(cyl.getWorldTransform().getBasis().getColumn(2));
  EXPECT_GT(std::fabs(axis.y()), 0.999) << "keeps rolling straight";
}

// Resting on a flat relief: each shape settles at its analytic height and stays there.
TEST(ReliefShapes, ShapesRestAtTheirHeightOnAFlatRelief) {
  SurfaceHolder s = holdSurface(flatRelief(128), 0.2, true);
  PhysicsWorld w;
  w.addReliefPlane(s.surface, kPlane);
  struct Case { const char* name; btRigidBody* body; double height; };
  Eigen::Isometry3d lying = at(0.05, 0, 0.0081);
  lying.linear() = Eigen::AngleAxisd(deg(90.0), Eigen::Vector3d::UnitX()).toRotationMatrix();
  Eigen::Isometry3d lying2 = lying;
  lying2.translation() = Eigen::Vector3d(-0.05, 0, 0.0081);
  Eigen::Isometry3d tipped = at(0, 0.05, 0.03);
  tipped.linear() = Eigen::AngleAxisd(deg(3.0), Eigen::Vector3d(1, 1, 0).normalized()).toRotationMatrix();
  const Case cases[] = {
      {"sphere", &w.addSphere(0.01, 0.05, at(0, 0, 0.0101), {0.5, 0, 0}), 0.01},
      {"box", &w.addBox({0.01, 0.015, 0.005}, 0.05, at(0, -0.05, 0.0052), {0.5, 0, 0}), 0.005},
      {"tipped box", &w.addBox({0.01, 0.01, 0.01}, 0.05, tipped, {0.5, 0, 0}), 0.01},
      {"capsule lying", &w.addCapsule(0.008, 0.01, 0.05, lying, {0.5, 0, 0}), 0.008},
      {"cylinder lying", &w.addCylinder(0.008, 0.01, 0.05, lying2, {0.5, 0, 0}), 0.008},
      {"cylinder standing", &w.addCylinder(0.008, 0.01, 0.05, at(0.05, 0.05, 0.0102), {0.5, 0, 0}), 0.01},
  };
  for (int k = 0; k < 500; ++k) w.step(kDt);
  for (const Case& c : cases) {
    EXPECT_NEAR(positionOf(*c.body).z(), c.height, 1e-4) << c.name;
    EXPECT_LT(velocityOf(*c.body).norm(), 1e-3) << c.name << " z " << positionOf(*c.body).z();
  }
}

// Unsupported shapes are not silently given wrong contacts: they find none and fall.
TEST(ReliefShapes, UnregisteredShapeFindsNoContacts) {
  SurfaceHolder s = holdSurface(flatRelief(64), 0.2, true);
  PhysicsWorld w;
  w.addReliefPlane(s.surface, kPlane);
  EXPECT_FALSE(undersideOf(btConeShapeZ(0.01f, 0.02f), Eigen::Isometry3d::Identity()).has_value());
}

}  // namespace
}  // namespace thx::phys::test::test_relief_contact
