// Rolling and spinning friction set in a scene's material slow a ball at the analytic rates and
// then hold it still. Both are Bullet's, lengths: the torque resisting the rolling (about an axis
// in the contact plane) or the spin (about the contact normal) is at most delta_c * N, with
// delta_c = delta_ball * mu_surface + delta_surface * mu_ball (Bullet's pair rule).
// Rolling: a ball rolling without slip under that torque: m a = -F, I a / r = F r - delta_c m g,
// so a = -(5/7) g delta_c / r. After the stop it is still: friction acts along the slip at any
// speed and the ball sleeps by the rest criterion (docs/physics.md, "Rest"); it used to slide on
// at 0.25 mm/s.
// Spinning: a ball spinning in place on a level plane, I dw/dt = -delta_c m g with I = 2/5 m r^2,
// so dw/dt = -(5/2) g delta_c / r^2. Bullet itself applies spinning friction only to contacts
// that also have rolling friction; the physics library adds it for the others
// (clients/physics/contact_solver.hpp), so both paths are checked.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "clients/physics_client/physics_scene.hpp"
#include "scenes/scene_loader.hpp"

namespace test_rolling_friction {

namespace {

using namespace thx::physclient;

constexpr double kRadius = 0.005, kSpeed = 0.2, kSpin = 20.0, kDelta = 1e-4, kMuWood = 0.6, kG = 9.81;

// A 5 mm steel ball on a level wood plane; `motion` gives its position and initial velocities.
std::string sceneYaml(const std::string& representation, const std::string& material, const std::string& motion) {
  const std::string generator = representation == "relief" ? "tilted, size: 256, params: {extent: 0.4, angle_deg: 0}"
                                                            : "tilted, size: 64, params: {extent: 0.4, angle_deg: 0}";
  return R"(version: 1
name: rolling_resistance
surface:
  size: [0.4, 0.4]
  texture: {generator: )" + generator + R"(}
  representation: )" + representation + R"(
  material: wood
objects:
  - name: ball
    shape: sphere
    radius: 0.005
    mass: 0.004
    material: )" + material + R"(
)" + motion;
}

const std::string kRolling = R"(    position: [-0.1, 0.0, 0.005]
    velocity: [0.2, 0.0, 0.0]
    angular_velocity: [0.0, 40.0, 0.0]
)";
const std::string kSpinning = R"(    position: [0.0, 0.0, 0.005]
    angular_velocity: [0.0, 0.0, 20.0]
)";

PhysicsScene simulate(const std::string& yaml) {
  const thx::scene::Scene scene = thx::scene::parseScene(yaml, "rolling.yaml", ".");
  SimOptions options;
  options.pen.shape = PenShape::None;
  return PhysicsScene(scene, options);
}

struct Outcome {
  double v_at_1s = 0.0, max_speed_after_stop = 0.0;
  double normal_over_weight = 0.0;  // mean normal force over the first second / m g
};

Outcome roll(const std::string& representation, double rate_hz) {
  PhysicsScene sim = simulate(sceneYaml(representation, "{name: steel, rolling_friction: 1e-4}", kRolling));
  Outcome o;
  const double dt = 1.0 / rate_hz;
  const int steps_1s = int(std::lround(rate_hz)), steps_4s = 4 * steps_1s;
  for (int k = 1; k <= steps_4s; ++k) {
    sim.step(dt);
    const double v = sim.body(0).v_world.norm();
    double impulse = 0.0;
    for (const LastingContact& c : sim.takeContacts()) impulse += c.impulse_sum_ns;
    if (k <= steps_1s) o.normal_over_weight += impulse / (0.004 * kG);
    if (k == steps_1s) o.v_at_1s = v;
    if (k >= 3 * steps_1s) o.max_speed_after_stop = std::max(o.max_speed_after_stop, v);
  }
  return o;
}

void expectAnalytic(const std::string& representation, double rate_hz) {
  const double a = 5.0 / 7.0 * kG * kDelta * kMuWood / kRadius;  // 0.0841 m/s²; stops at 2.38 s
  const Outcome o = roll(representation, rate_hz);
  std::printf("[measured] %s %g Hz: v(1 s) = %.5f m/s (analytic %.5f), max speed 3-4 s %.2e m/s, N/mg %.4f\n",
              representation.c_str(), rate_hz, o.v_at_1s, kSpeed - a, o.max_speed_after_stop, o.normal_over_weight);
  EXPECT_NEAR(kSpeed - o.v_at_1s, a, 0.02 * a);  // the speed lost in 1 s, within 2 %
  // Stopped and silent (below 0.01 mm/s) from 3 s on.
  EXPECT_LT(o.max_speed_after_stop, 1e-5);
}

TEST(RollingFriction, NormalMapAt1000HzMatchesTheAnalyticDeceleration) { expectAnalytic("normal", 1000); }
TEST(RollingFriction, NormalMapAt60HzMatchesTheAnalyticDeceleration) { expectAnalytic("normal", 60); }
TEST(RollingFriction, ReliefAt1000HzMatchesTheAnalyticDeceleration) { expectAnalytic("relief", 1000); }

struct SpinOutcome {
  double spin_at_100ms = 0.0;         // rad/s, about the vertical
  double max_speed_after_stop = 0.0;  // m/s, of the centre, from 0.5 s on
  double max_spin_after_stop = 0.0;   // rad/s
};

SpinOutcome spin(const std::string& representation, const std::string& material, double rate_hz) {
  PhysicsScene sim = simulate(sceneYaml(representation, material, kSpinning));
  SpinOutcome o;
  const double dt = 1.0 / rate_hz;
  const int steps = int(std::lround(0.7 * rate_hz)), at_100ms = int(std::lround(0.1 * rate_hz));
  for (int k = 1; k <= steps; ++k) {
    sim.step(dt);
    const BodyState b = sim.body(0);
    if (k == at_100ms) o.spin_at_100ms = b.w_world.z();
    if (double(k) * dt < 0.5) continue;
    o.max_speed_after_stop = std::max(o.max_speed_after_stop, b.v_world.norm());
    o.max_spin_after_stop = std::max(o.max_spin_after_stop, b.w_world.norm());
  }
  return o;
}

void expectAnalyticSpin(const std::string& representation, const std::string& material, double rate_hz) {
  const double alpha = 2.5 * kG * kDelta * kMuWood / (kRadius * kRadius);  // 58.86 rad/s²; stops at 0.34 s
  const SpinOutcome o = spin(representation, material, rate_hz);
  const double lost = kSpin - o.spin_at_100ms, expected = alpha * 0.1;
  std::printf("[measured] spin, %s, %s, %g Hz: lost in 0.1 s %.4f rad/s (analytic %.4f, %+.2f %%); from 0.5 s "
              "max speed %.2e m/s, max spin %.2e rad/s\n",
              representation.c_str(), material.c_str(), rate_hz, lost, expected, 100.0 * (lost / expected - 1.0),
              o.max_speed_after_stop, o.max_spin_after_stop);
  EXPECT_NEAR(lost, expected, 0.02 * expected);  // within 2 %
  // Stopped and still: no spin left, the centre silent (below 0.01 mm/s).
  EXPECT_LT(o.max_spin_after_stop, 1e-3);
  EXPECT_LT(o.max_speed_after_stop, 1e-5);
}

const std::string kSpinningOnly = "{name: steel, spinning_friction: 1e-4}";
// Bullet's own path: with rolling friction on the contact it adds the spinning row itself.
const std::string kSpinningAndRolling = "{name: steel, spinning_friction: 1e-4, rolling_friction: 1e-4}";

TEST(SpinningFriction, NormalMapAt1000HzMatchesTheAnalyticDeceleration) { expectAnalyticSpin("normal", kSpinningOnly, 1000); }
TEST(SpinningFriction, NormalMapAt60HzMatchesTheAnalyticDeceleration) { expectAnalyticSpin("normal", kSpinningOnly, 60); }
TEST(SpinningFriction, ReliefAt1000HzMatchesTheAnalyticDeceleration) { expectAnalyticSpin("relief", kSpinningOnly, 1000); }
TEST(SpinningFriction, WithRollingFrictionTheSameDeceleration) { expectAnalyticSpin("normal", kSpinningAndRolling, 1000); }

// Without spinning friction nothing resists the spin (a point contact has no patch).
TEST(SpinningFriction, WithoutItTheBallSpinsOn) {
  PhysicsScene sim = simulate(sceneYaml("normal", "steel", kSpinning));
  for (int k = 0; k < 100; ++k) sim.step(1e-3);
  EXPECT_NEAR(sim.body(0).w_world.z(), kSpin, 1e-3);
}

TEST(RollingAndSpinningFriction, SceneFieldErrorsNameTheFieldAndTheValue) {
  for (const std::string field : {"rolling_friction: 0.5", "spinning_friction: -1"}) {
    const std::string bad = sceneYaml("normal", "{name: steel, " + field + "}", "    position: [0, 0, 0.005]\n");
    try {
      thx::scene::parseScene(bad, "bad.yaml", ".");
      ADD_FAILURE() << "accepted " << field;
    } catch (const std::exception& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(field.substr(0, field.find(':'))), std::string::npos) << what;
      EXPECT_NE(what.find(field.substr(field.find(' ') + 1)), std::string::npos) << what;
    }
  }
}

}  // namespace

}  // namespace test_rolling_friction
