// A plain ball in a V-groove of a relief mesh or a textured box (issue 29; mesh_contact.hpp,
// ballOnReliefContacts, applyBallMeshManifold): where the ball's lift has a crease under its centre
// (the groove's floor, or the two rims of a groove narrower than the ball) it is met by one
// contact for each side of the crease, each wall's own normal and gap, and rests as in a wedge.
// Before (one normal blended across the crease over a quarter texel) it rocked from rim to rim
// without rolling friction and a force applied at once started it up a wall below the wall's
// slope. The relief plane meets it with its own candidates and is the reference.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>

#include "tests/physics/rod_in_groove_scene.hpp"

namespace thx::phys::test {
namespace {

using namespace rod_in_groove;

constexpr Ground kMeshGrounds[] = {Ground::FlatMesh, Ground::Box};
const char* nameOf(Ground g) { return g == Ground::FlatMesh ? "flat mesh" : "textured box"; }

// The ball's manifold with the ground (the only one in these scenes).
const btPersistentManifold* ballManifold(PhysicsWorld& world) {
  btDispatcher* dispatcher = world.world().getDispatcher();
  for (int m = 0; m < dispatcher->getNumManifolds(); ++m)
    if (dispatcher->getManifoldByIndexInternal(m)->getNumContacts() > 0) return dispatcher->getManifoldByIndexInternal(m);
  return nullptr;
}

TEST(BallInAVGroove, ItRestsOnBothWallsWhereItDoesOnThePlane) {
  const RodScene on_plane(Ground::Plane, Rod::Ball);
  // The texels' sampling leaves it 16 µm above its circle touching both walls at 0.31 mm texels.
  EXPECT_NEAR(on_plane.rest.z(), inTheGroove(kRadius), 2.5e-5);
  for (const Ground ground : kMeshGrounds) {
    RodScene s(ground, Rod::Ball);
    EXPECT_NEAR(s.rest.z(), on_plane.rest.z(), 1e-8) << nameOf(ground);
    EXPECT_NEAR(s.rest.x(), 0.5 * kPeriod, 1e-6) << nameOf(ground);
    // One contact on each wall, each pushing with the wall's normal (the ground's top is level).
    s.world->step(kDt);
    const btPersistentManifold* manifold = ballManifold(*s.world);
    ASSERT_NE(manifold, nullptr);
    ASSERT_EQ(manifold->getNumContacts(), 2) << nameOf(ground);
    double sum = 0.0;
    for (int k = 0; k < 2; ++k) {
      const btVector3 n = manifold->getContactPoint(k).m_normalWorldOnB * (manifold->getBody0() == s.rod ? 1 : -1);
      EXPECT_NEAR(std::fabs(n.x()), std::sin(kWall), 1e-3) << nameOf(ground);
      sum += n.x();
    }
    EXPECT_NEAR(sum, 0.0, 1e-4) << nameOf(ground);
  }
}

TEST(BallInAVGroove, PushedAtOnceItLeavesOnlyAboveTanWallOfItsWeight) {
  // Before, at 0.468 of its weight (128 texels; 0.485 at 256), one normal at the floor blended
  // over a quarter texel letting it gather speed before it met a wall's full slope.
  for (const Ground ground : kMeshGrounds) {
    const Eigen::Vector3d held = RodScene(ground, Rod::Ball).push(0.49);
    const Eigen::Vector3d leaves = RodScene(ground, Rod::Ball).push(0.52);
    EXPECT_LT(held.norm(), 1e-4) << nameOf(ground) << ": " << held.transpose();
    EXPECT_GT(leaves.x(), 2 * kPeriod) << nameOf(ground) << ": " << leaves.transpose();
  }
}

TEST(BallInAVGroove, OnTheRimsWithoutRollingFrictionItIsStill) {
  // A 5 mm ball rests on the two rims 4 mm apart; kept awake, let down over the floor and off it.
  // Before, it rocked from rim to rim at 0.99-1.35 mm/s in its third second.
  for (const Ground ground : kMeshGrounds) {
    for (const double x : {0.0, 0.4e-3, 1.0e-3}) {
      RodScene s(ground, Rod::Ball, 128, 0.005, x);
      double fastest = 0.0;
      for (int k = 0; k < 2500; ++k) {
        s.rod->activate(true);
        s.world->step(kDt);
        if (k >= 1500) fastest = std::max(fastest, double(s.rod->getLinearVelocity().length()));
      }
      std::printf("[measured] %s, let down %.1f mm off the floor: fastest in its third second %.4f mm/s\n", nameOf(ground),
                  x * 1e3, fastest * 1e3);
      EXPECT_LT(fastest, 1e-5) << nameOf(ground) << " " << x;
      // On the rims: sqrt(r^2 - (P/2)^2) over the ridges, to the texels' sampling.
      EXPECT_NEAR(positionOf(*s.rod).z(), std::sqrt(0.005 * 0.005 - 0.25 * kPeriod * kPeriod), 1e-5) << nameOf(ground);
    }
  }
}

// A ball rolling with rolling friction mu_r (a length) slows at mu_r g cos a / (r (cos^2 a + 2/5))
// where its contacts lean a from the vertical: each contact resists the roll by mu_r times its own
// load (the loads sum to m g / cos a) about its tangent, which the roll's axis leans from by a, and
// the ball turns at v / (r cos a). On a flat relief (one contact, a = 0) that is 5/7 mu_r g / r. In
// the groove its two contacts share one manifold: Bullet 3.24 gives every point of a manifold its
// own rolling rows, so the second wall's load resists too (the first point's load alone would
// halve it). Measured +2.3 % in the groove at 128, 256 and 512 texels alike: the two walls'
// friction rows hold a squeeze, pushing the ball down by 2.3 % of its weight, which their normal
// impulses carry as well (no slip: 0.1 µm/s at 38 mm/s).
double vGrooveRollingDeceleration(bool in_the_groove) {
  constexpr double kRolling = 1e-4, kSpeed = 0.1;
  const SurfaceHolder relief =
      holdSurface(in_the_groove ? heightMap(128, kExtent, vGrooves) : flatRelief(128), kExtent, true);
  PhysicsWorld world;
  world.addReliefPlane(relief.surface, {1.0, 0.0, 0.0});
  const double lean = in_the_groove ? kWall : 0.0;
  const double z = in_the_groove ? inTheGroove(kRadius) : kRadius;
  btRigidBody& ball = world.addSphere(kRadius, kRodMass, at(0.5 * kPeriod, 0.0, z + 1e-5), {kFriction, 0.0, kRolling, 0.0});
  for (int k = 0; k < 200; ++k) world.step(kDt);
  ball.setLinearVelocity(btVector3(0, btScalar(kSpeed), 0));
  ball.setAngularVelocity(btVector3(btScalar(-kSpeed / (kRadius * std::cos(lean))), 0, 0));
  for (int k = 0; k < 50; ++k) world.step(kDt);
  const double v0 = ball.getLinearVelocity().y();
  constexpr int kSteps = 200;
  for (int k = 0; k < kSteps; ++k) world.step(kDt);
  const double measured = (v0 - ball.getLinearVelocity().y()) / (kSteps * kDt);
  const double c = std::cos(lean);
  const double expected = kRolling * kG * c / (kRadius * (c * c + 0.4));
  std::printf("[measured] rolling %s: slows at %.4f m/s^2 against mu_r g cos a / (r (cos^2 a + 2/5)) = %.4f (%+.2f %%)\n",
              in_the_groove ? "along a V-groove on both walls" : "on a flat relief", measured, expected,
              100.0 * (measured / expected - 1.0));
  EXPECT_NEAR(positionOf(ball).x(), 0.5 * kPeriod, 1e-5) << "it stays over the groove's floor";
  return measured / expected;
}

TEST(BallInAVGroove, RollingAlongItSlowsByItsRollingFrictionTimesTheLoadOnBothWalls) {
  EXPECT_NEAR(vGrooveRollingDeceleration(false), 1.0, 0.01);
  EXPECT_NEAR(vGrooveRollingDeceleration(true), 1.0, 0.04);
}

}  // namespace
}  // namespace thx::phys::test
