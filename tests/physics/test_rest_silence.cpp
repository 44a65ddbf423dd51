// A resting object is silent: its speed and the slip its contacts report both stay below
// 0.01 mm/s (what an audio client turns into sound must be zero at rest). Each resting case at
// 1 kHz and at 60 Hz: a ball on a groove's two walls, a box on a flat normal map and on a flat
// relief, a ball rolled to a stop by rolling friction, a ball in a dimple of its own radius (a
// conforming contact). The mechanism: docs/physics.md, "Rest".
#include <gtest/gtest.h>

#include <BulletCollision/NarrowPhaseCollision/btPersistentManifold.h>

#include <algorithm>
#include <cstdio>

#include "clients/physics/bullet_convert.hpp"
#include "physics_fixtures.hpp"

namespace thx::phys::test::test_rest_silence {
namespace {

constexpr double kSilent = 1e-5;  // m/s: 0.01 mm/s

struct Quiet {
  double max_speed = 0.0;  // of the body's centre
  double max_slip = 0.0;   // tangential relative velocity at any of its contact points
};

// The slip a contact reports: the body's velocity at the contact point, along the contact plane
// (the other body is static in these cases).
double maxSlip(PhysicsWorld& w, const btRigidBody& body) {
  double worst = 0.0;
  btDispatcher& dispatcher = *w.world().getDispatcher();
  for (int m = 0; m < dispatcher.getNumManifolds(); ++m) {
    const btPersistentManifold& manifold = *dispatcher.getManifoldByIndexInternal(m);
    if (manifold.getBody0() != &body && manifold.getBody1() != &body) continue;
    for (int k = 0; k < manifold.getNumContacts(); ++k) {
      const btManifoldPoint& p = manifold.getContactPoint(k);
      const Eigen::Vector3d n = toEigen(p.m_normalWorldOnB);
      const Eigen::Vector3d at = toEigen(manifold.getBody0() == &body ? p.getPositionWorldOnA() : p.getPositionWorldOnB());
      const Eigen::Vector3d v = velocityOf(body) + angularVelocityOf(body).cross(at - positionOf(body));
      worst = std::max(worst, (v - v.dot(n) * n).norm());
    }
  }
  return worst;
}

// Steps `seconds`; measures from `settle_s` on (every case here is asleep by 0.9 s).
Quiet quietAfter(PhysicsWorld& w, btRigidBody& body, double dt, double settle_s, double seconds) {
  Quiet q;
  const int steps = int(std::lround(seconds / dt));
  for (int k = 1; k <= steps; ++k) {
    w.step(dt);
    if (double(k) * dt < settle_s) continue;
    q.max_speed = std::max(q.max_speed, velocityOf(body).norm());
    q.max_slip = std::max(q.max_slip, maxSlip(w, body));
  }
  return q;
}

void expectSilent(const Quiet& q, const char* what, double dt) {
  std::printf("[measured] %s at %.0f Hz: max speed %.3g m/s, max contact slip %.3g m/s\n", what, 1.0 / dt, q.max_speed,
              q.max_slip);
  EXPECT_LT(q.max_speed, kSilent) << what;
  EXPECT_LT(q.max_slip, kSilent) << what;
}

class RestSilence : public ::testing::TestWithParam<double> {};  // time step

TEST_P(RestSilence, BallOnAGroovesWalls) {
  const SurfaceHolder s = holdSurface(heightMap(256, 0.1, uGroove), 0.1, true);
  PhysicsWorld w;
  w.addReliefPlane(s.surface, {1.0, 0.0, 0.0});
  btRigidBody& ball = w.addSphere(0.006, 0.0009, at(0.0002, 0, 0.00465), {0.5, 0.0, 0.0});
  expectSilent(quietAfter(w, ball, GetParam(), 1.0, 2.0), "ball on a groove's walls", GetParam());
}

// A dimple whose cap has the ball's radius (scenes/dimple_ball.yaml): the ball touches it
// everywhere at once. Before its contacts were chosen by position (conforming_contact.hpp) it
// rocked in a two-step cycle (2.3 mm/s at 1 kHz) and bounced up to 1.5 mm into the cap at 60 Hz
// (98 mm/s); now it sleeps by 0.29 s (1 kHz) / 0.58 s (60 Hz), its centre within 0.5 µm of the
// cap's centre.
double conformingDimple(double x, double y) {
  const double a = 0.004, dep = 0.002, cap = (a * a + dep * dep) / (2.0 * dep);  // 5 mm
  const double r2 = x * x + y * y;
  return r2 < a * a ? -(std::sqrt(cap * cap - r2) - (cap - dep)) : 0.0;
}

TEST_P(RestSilence, BallInAConformingDimple) {
  const SurfaceHolder s = holdSurface(heightMap(256, 0.1, conformingDimple), 0.1, true);
  PhysicsWorld w;
  w.addReliefPlane(s.surface, {1.0, 0.0, 0.0});
  btRigidBody& ball = w.addSphere(0.005, 0.00411, at(0.0003, -0.0002, 0.00305), {0.5, 0.0, 0.0});
  expectSilent(quietAfter(w, ball, GetParam(), 1.0, 2.0), "ball in a conforming dimple", GetParam());
}

TEST_P(RestSilence, BoxOnAFlatNormalMap) {
  const SurfaceHolder s = holdSurface(tiltedMap(0.0, 64, 0.2), 0.2, false);
  PhysicsWorld w;
  w.addNormalMapPlane(s.surface, {1.0, 0.0, 0.0});
  btRigidBody& box = w.addBox({0.01, 0.01, 0.005}, 0.003, at(0, 0, 0.0051), {0.5, 0.0, 0.0});
  expectSilent(quietAfter(w, box, GetParam(), 1.0, 2.0), "box on a flat normal map", GetParam());
}

TEST_P(RestSilence, BoxOnAFlatRelief) {
  // 64² texels (1.6 mm; flat, so their size does not matter): the sanitizer build rasterises a
  // relief box slowly.
  const SurfaceHolder s = holdSurface(flatRelief(64), 0.1, true);
  PhysicsWorld w;
  w.addReliefPlane(s.surface, {1.0, 0.0, 0.0});
  btRigidBody& box = w.addBox({0.01, 0.01, 0.005}, 0.003, at(0, 0, 0.0051), {0.5, 0.0, 0.0});
  expectSilent(quietAfter(w, box, GetParam(), 1.0, 2.0), "box on a flat relief", GetParam());
}

// Rolling friction stops a ball rolling at 5 cm/s after 0.6 s (a = 5/7 g delta / r); from then
// on it must be still, not slide on (asleep from 0.87 s).
TEST_P(RestSilence, BallRolledToAStopByRollingFriction) {
  const SurfaceHolder s = holdSurface(tiltedMap(0.0, 64, 0.4), 0.4, false);
  PhysicsWorld w;
  w.addNormalMapPlane(s.surface, {1.0, 0.0, 0.0});
  btRigidBody& ball = w.addSphere(0.005, 0.004, at(-0.1, 0, 0.005), {0.5, 0.0, 6e-5});
  setRolling(ball, 0.05, 0.005);
  expectSilent(quietAfter(w, ball, GetParam(), 1.0, 2.0), "ball stopped by rolling friction", GetParam());
}

// Sleeping is Bullet's: a ball asleep on the plane wakes when another ball rolls into it, and a
// kinematic body (the physics client's pen) wakes it by touching it.
TEST_P(RestSilence, AsleepBallWakesWhenTouched) {
  const SurfaceHolder s = holdSurface(tiltedMap(0.0, 64, 0.4), 0.4, false);
  const double dt = GetParam();
  PhysicsWorld w;
  w.addNormalMapPlane(s.surface, {1.0, 0.0, 0.0});
  btRigidBody& resting = w.addSphere(0.005, 0.004, at(0, 0, 0.005), {0.5, 0.0, 0.0});
  btRigidBody& pen = w.addSphere(0.004, 0.0, at(0.0, 0.1, 0.004), {0.5, 0.0, 0.0});
  pen.setCollisionFlags(pen.getCollisionFlags() | btCollisionObject::CF_KINEMATIC_OBJECT);
  pen.setActivationState(DISABLE_DEACTIVATION);
  for (int k = 0; k < int(std::lround(1.0 / dt)); ++k) w.step(dt);
  ASSERT_EQ(resting.getActivationState(), ISLAND_SLEEPING);

  // A second ball rolls into it at 0.1 m/s along +x.
  btRigidBody& rolling = w.addSphere(0.005, 0.004, at(-0.03, 0, 0.005), {0.5, 0.0, 0.0});
  setRolling(rolling, 0.1, 0.005);
  for (int k = 0; k < int(std::lround(0.5 / dt)); ++k) w.step(dt);
  std::printf("[measured] hit at %.0f Hz: the sleeper moved %.2f mm\n", 1.0 / dt, positionOf(resting).x() * 1e3);
  EXPECT_GT(positionOf(resting).x(), 0.005);

  // Both asleep again; then the kinematic pen moves into the first along -y at 0.1 m/s.
  for (int k = 0; k < int(std::lround(3.0 / dt)); ++k) w.step(dt);
  const Eigen::Vector3d before = positionOf(resting);
  for (int k = 1; k <= int(std::lround(1.0 / dt)); ++k) {
    btTransform t = pen.getWorldTransform();
    t.setOrigin(toBt(Eigen::Vector3d(before.x(), 0.1 - 0.1 * k * dt, 0.004)));
    pen.setWorldTransform(t);
    w.step(dt);
  }
  std::printf("[measured] pen at %.0f Hz: the sleeper moved %.2f mm\n", 1.0 / dt, (positionOf(resting) - before).norm() * 1e3);
  EXPECT_GT((positionOf(resting) - before).norm(), 0.005);
}

INSTANTIATE_TEST_SUITE_P(TimeStep, RestSilence, ::testing::Values(1e-3, 1.0 / 60.0),
                         [](const auto& p) { return p.param < 0.01 ? "1kHz" : "60Hz"; });

}  // namespace
}  // namespace thx::phys::test::test_rest_silence
