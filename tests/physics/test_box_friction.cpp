// A box with Coulomb friction sliding down a virtual slope (a uniformly tilted normal map on a
// flat plane). The plane holds the box's height, the contact pushes along n_s (tilted θ towards
// +x) and friction acts along the slope's tangent, so the vertical balance
// N (cosθ + μ sinθ) = m g gives a = g (tanθ − μ) / (1 + μ tanθ) horizontally.
//
// This used to come out 12 % slow at θ = 10°, μ = 0.1: Bullet's solver skips (and so keeps) the
// friction impulse of a contact whose normal impulse dropped to zero during its iterations, and
// a box rocking on its corners has such contacts every step; measured tangential impulse was
// 1.09 μ × normal impulse. ContactSolver (clients/physics/contact_solver.hpp) releases it.
#include <gtest/gtest.h>

#include <cstdio>

#include "clients/physics/bullet_convert.hpp"
#include "clients/physics/contact_solver.hpp"
#include "physics_fixtures.hpp"

namespace thx::phys::test::test_box_friction {
namespace {

constexpr double kDt = 1e-3, kHalf = 0.01, kMass = 0.05;

struct Slide {
  double accel = 0.0;         // horizontal (along the slope for a real slope), between 0.1 and 0.5 s
  double friction_ratio = 0;  // Σ tangential impulse / Σ normal impulse, from the box's momentum
  long long released = 0;     // friction rows ContactSolver released over the run
};

// Impulse the contacts gave the box in one step: m Δv minus gravity's share.
Eigen::Vector3d contactImpulse(const Eigen::Vector3d& v_before, const Eigen::Vector3d& v_after,
                               const Eigen::Vector3d& gravity) {
  return kMass * (v_after - v_before) - kMass * gravity * kDt;
}

Slide runSlide(PhysicsWorld& w, btRigidBody& box, const Eigen::Vector3d& n_contact, const Eigen::Vector3d& downhill) {
  Slide s;
  const auto* solver = dynamic_cast<const ContactSolver*>(w.world().getConstraintSolver());
  EXPECT_NE(solver, nullptr) << "PhysicsWorld uses ContactSolver";
  const Eigen::Vector3d gravity = w.options().gravity_m_per_s2;
  double v1 = 0.0, sum_n = 0.0, sum_t = 0.0;
  for (int k = 1; k <= 500; ++k) {
    const Eigen::Vector3d before = velocityOf(box);
    w.step(kDt);
    if (solver) s.released += solver->releasedFrictionRows();
    if (k > 100) {
      const Eigen::Vector3d j = contactImpulse(before, velocityOf(box), gravity);
      sum_n += j.dot(n_contact);
      sum_t += (j - j.dot(n_contact) * n_contact).norm();
    }
    if (k == 100) v1 = velocityOf(box).dot(downhill);
  }
  s.accel = (velocityOf(box).dot(downhill) - v1) / 0.4;
  s.friction_ratio = sum_t / sum_n;
  return s;
}

Slide slideOnNormalMap(double angle_deg, double mu, bool hold_height) {
  SurfaceHolder s = holdSurface(tiltedMap(angle_deg, 64, 0.2), 0.2, false);
  PhysicsWorld w;
  NormalMapOptions o;
  o.hold_height = hold_height;
  w.addNormalMapPlane(s.surface, {1.0, 0.0, 0.0}, o);  // Bullet multiplies frictions: the box's decides
  btRigidBody& box = w.addBox({kHalf, kHalf, kHalf}, kMass, at(0, 0, kHalf), {mu, 0.0, 0.0});
  const Eigen::Vector3d n_s(std::sin(deg(angle_deg)), 0.0, std::cos(deg(angle_deg)));
  Slide r = runSlide(w, box, n_s, Eigen::Vector3d::UnitX());
  const Eigen::Vector3d up = toEigen(box.getWorldTransform().getBasis().getColumn(2));
  EXPECT_GT(up.z(), std::cos(deg(1.0))) << "slides flat";
  return r;
}

double virtualSlope(double angle_deg, double mu) {
  const double t = std::tan(deg(angle_deg));
  return kG * (t - mu) / (1.0 + mu * t);
}

TEST(BoxFrictionNormalMap, SlidesAtTheVirtualSlopeAcceleration) {
  struct Case { double angle, mu; };
  for (const Case c : {Case{10.0, 0.1}, Case{20.0, 0.1}, Case{15.0, 0.2}}) {
    const Slide s = slideOnNormalMap(c.angle, c.mu, true);
    const double expected = virtualSlope(c.angle, c.mu);
    std::printf("[measured] box on normal map %g deg, mu %g: a = %.5f, expected %.5f (%+.2f %%), friction/normal %.4f\n",
                c.angle, c.mu, s.accel, expected, 100.0 * (s.accel / expected - 1.0), s.friction_ratio);
    EXPECT_NEAR(s.accel, expected, 0.015 * expected) << c.angle << " deg, mu " << c.mu;
  }
}

TEST(BoxFrictionNormalMap, WithoutTheHeightHoldToo) {
  const Slide s = slideOnNormalMap(10.0, 0.1, false);
  const double expected = virtualSlope(10.0, 0.1);
  EXPECT_NEAR(s.accel, expected, 0.015 * expected);
}

TEST(BoxFrictionNormalMap, FrictionNeverExceedsMuTimesTheNormalImpulse) {
  const double mu = 0.1;
  const Slide s = slideOnNormalMap(10.0, mu, true);
  // Sliding all the time: the ratio is μ exactly when no contact keeps friction without load.
  EXPECT_LT(s.friction_ratio, mu * 1.002);
  EXPECT_GT(s.friction_ratio, mu * 0.99) << "and it still slides with full Coulomb friction";
  EXPECT_GT(s.released, 0) << "the rocking box does produce the case ContactSolver corrects";
}

// Bullet's own contacts on a real slope are unchanged by the solver: g (sinθ − μ cosθ).
TEST(BoxFrictionRealSlope, BulletsOwnContactsStillSlideAtGSinMinusMuCos) {
  const double angle = 10.0, mu = 0.1;
  Eigen::Isometry3d plane = Eigen::Isometry3d::Identity();
  plane.linear() = Eigen::AngleAxisd(deg(angle), Eigen::Vector3d::UnitY()).toRotationMatrix();
  PhysicsWorld w;
  w.addPlainPlane(plane, {1.0, 0.0, 0.0});
  Eigen::Isometry3d pose = plane;
  pose.translation() = plane.linear() * Eigen::Vector3d(0, 0, kHalf);
  btRigidBody& box = w.addBox({kHalf, kHalf, kHalf}, kMass, pose, {mu, 0.0, 0.0});
  const Eigen::Vector3d n = plane.linear().col(2), downhill = plane.linear().col(0);
  const Slide s = runSlide(w, box, n, downhill);
  const double expected = kG * (std::sin(deg(angle)) - mu * std::cos(deg(angle)));
  EXPECT_NEAR(s.accel, expected, 0.01 * expected);
  EXPECT_LT(s.friction_ratio, mu * 1.002);
}

}  // namespace
}  // namespace thx::phys::test::test_box_friction
