// Two objects striking each other (issue 14: every contact excites both sides): the physics
// client's core reports one impact naming both balls, the normal from b to a, the contact point
// between them and the normal impulse each ball's momentum changed by in that step. Gravity off,
// so nothing but the two balls acts on them.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "clients/physics_client/physics_scene.hpp"
#include "scenes/scene_loader.hpp"

namespace test_object_impacts {

namespace {

using namespace thx::physclient;

// Ball 0 (steel, r 8 mm) flies at +x towards ball 1 (glass, r 6 mm) at rest, 5 cm above a flat
// plane, centres on one line: a head-on impact at the first touch, 10 mm of flight after 25 ms.
const std::string kScene = R"(version: 1
name: two_balls
surface: {size: [0.1, 0.1], representation: normal, material: wood,
          texture: {generator: tilted, size: 32, params: {extent: 0.1, angle_deg: 0}}}
objects:
  - {name: a, shape: sphere, radius: 0.008, mass: 0.0168, material: steel, position: [-0.02, 0, 0.05], velocity: [0.4, 0, 0]}
  - {name: b, shape: sphere, radius: 0.006, mass: 0.00226, material: glass, position: [0.0, 0, 0.05]}
)";

TEST(ObjectImpacts, TwoBallsGiveOneImpactWithBothIdsAndTheExchangedMomentum) {
  const thx::scene::Scene scene = thx::scene::parseScene(kScene, "two_balls.yaml", ".");
  SimOptions options;
  options.world.gravity_m_per_s2.setZero();
  options.pen.shape = PenShape::None;
  PhysicsScene sim(scene, options);
  const double ma = scene.objects[0].mass_kg, mb = scene.objects[1].mass_kg;
  const double dt = 1e-3;

  int impacts = 0;
  Impact hit;
  BodyState a_before, b_before, a_after, b_after;
  for (int k = 0; k < 100; ++k) {
    const BodyState a0 = sim.body(0), b0 = sim.body(1);
    sim.step(dt);
    for (const Impact& i : sim.impacts()) {
      ++impacts;
      hit = i;
      a_before = a0, b_before = b0, a_after = sim.body(0), b_after = sim.body(1);
    }
  }
  ASSERT_EQ(impacts, 1) << "one impact, then the balls part";
  EXPECT_EQ(hit.body_a, 0);  // the lower index is a
  EXPECT_EQ(hit.body_b, 1);
  EXPECT_FALSE(hit.on_surface);
  // 6 mm between the surfaces close at 0.4 m/s in 15 ms; Bullet finds contacts at the start of a
  // step, before it moves the bodies, so the impact is in one of the two steps after the touch
  // (measured: 17 ms, the balls 0.4 mm into each other at its start).
  EXPECT_GE(hit.sim_time_s, 0.015 + 0.5 * dt);
  EXPECT_LE(hit.sim_time_s, 0.017 + 0.5 * dt);
  // The normal points from b towards a (-x); the point lies between the centres, on both surfaces.
  EXPECT_NEAR(hit.n_world.x(), -1.0, 1e-6);
  EXPECT_NEAR(hit.v_approach_m_per_s, 0.4, 1e-6);
  const double gap = (b_after.p_world - a_after.p_world).norm();
  EXPECT_NEAR((hit.p_world - a_after.p_world).norm(), 0.008, 0.0005 + std::fabs(gap - 0.014));
  EXPECT_NEAR((hit.p_world - b_after.p_world).norm(), 0.006, 0.0005 + std::fabs(gap - 0.014));

  // The reported impulse is what each ball's momentum changed by in the impact step, opposite.
  const double dpa = ma * (a_after.v_world - a_before.v_world).x();
  const double dpb = mb * (b_after.v_world - b_before.v_world).x();
  std::printf("[measured] impact at %.4f s, centres %.4f mm apart before the step, %.4f after; impulse %.6g N s; ball a dp "
              "%.6g, ball b dp %.6g; after: a %.4g m/s, b %.4g m/s\n",
              hit.sim_time_s, 1e3 * (b_before.p_world - a_before.p_world).norm(), 1e3 * gap, hit.impulse_ns, dpa, dpb,
              a_after.v_world.x(), b_after.v_world.x());
  EXPECT_GT(hit.impulse_ns, 0.0);
  EXPECT_NEAR(-dpa, hit.impulse_ns, 1e-6 * hit.impulse_ns + 1e-9);
  EXPECT_NEAR(dpb, hit.impulse_ns, 1e-6 * hit.impulse_ns + 1e-9);
  // Between a perfectly plastic and a perfectly elastic impact: m* v (1 + e), e in [0, 1].
  const double m_eff = ma * mb / (ma + mb);
  EXPECT_GE(hit.impulse_ns, m_eff * 0.4 * (1 - 1e-6));
  EXPECT_LE(hit.impulse_ns, 2 * m_eff * 0.4 * (1 + 1e-6));
}

}  // namespace

}  // namespace test_object_impacts
