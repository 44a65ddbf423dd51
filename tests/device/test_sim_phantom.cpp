// The simulated PHANToM's device contract, lock-step: readings (encoder quantisation,
// finite-difference velocity, buttons), the zero-order hold, motor saturation, the watchdog on
// missing writes and missed ticks, fault injection, plane rendering, determinism.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "device/sim_phantom.hpp"

namespace test_sim_phantom {

using namespace thx::dev;

namespace {

constexpr double kT = 1e-3;

// Pen and hand as one free mass: no hand spring or damper, no mechanism damping or friction, so
// velocity changes come from the motor force alone.
SimPhantomConfig freeMassConfig() {
  SimPhantomConfig c;
  c.hand_stiffness_n_per_m = 0.0;
  c.hand_damping_ns_per_m = 0.0;
  c.friction_n = 0.0;
  c.spec.physical_damping_ns_per_m = 0.0;
  return c;
}

double massOf(const SimPhantomConfig& c) { return c.device_mass_kg + c.hand_mass_kg; }

DeviceCommand forceCommand(const Eigen::Vector3d& f) {
  DeviceCommand cmd;
  cmd.forces_enabled = true;
  cmd.force_world_n = f;
  return cmd;
}

// Plain wall z <= 0 rendered by the servo from the reading.
DeviceCommand wall(const DeviceState& s, double k_n_per_m) {
  return forceCommand(Eigen::Vector3d(0, 0, k_n_per_m * std::max(0.0, -s.p_world.z())));
}

}  // namespace

TEST(SimPhantom, DesktopSpec) {
  const DeviceSpec s = phantomDesktopSpec();
  EXPECT_EQ(s.model, "phantom_desktop");
  EXPECT_EQ(s.peak_force_n, 7.9);
  EXPECT_NEAR(s.continuous_force_n, 1.185, 1e-12);
  EXPECT_EQ(s.max_stiffness_n_per_m, 1000.0);
  EXPECT_EQ(s.max_damping_ns_per_m, 5.0);
  EXPECT_EQ(s.workspace_radius_m, 0.10);
  EXPECT_EQ(s.position_resolution_m, 2.3e-5);
  EXPECT_GT(s.physical_damping_ns_per_m, 0.0);
  EXPECT_LE(s.physical_damping_ns_per_m, 0.05);
}

TEST(SimPhantom, InvalidConfigIsRejectedWithTheField) {
  const auto message = [](SimPhantomConfig c) {
    try {
      SimPhantom sim(c);
    } catch (const DeviceError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  SimPhantomConfig c;
  c.integration_hz = 10500;
  EXPECT_NE(message(c).find("SimPhantomConfig.integration_hz: not a whole number >= 10 of steps per servo tick"),
            std::string::npos);
  c.integration_hz = 5000;
  EXPECT_NE(message(c).find("got '5000 Hz with a 1000000 ns tick'"), std::string::npos);
  c = SimPhantomConfig{};
  c.hand_mass_kg = -1.0;
  EXPECT_EQ(message(c), "SimPhantomConfig.hand_mass_kg: out of range; expected a mass > 0 kg, got '-1'");
  c = SimPhantomConfig{};
  c.friction_velocity_scale_m_per_s = 1e-6;  // 60000 N·s/m of viscous friction: too stiff at 10 kHz
  EXPECT_NE(message(c).find("integration_hz: too low for the damping"), std::string::npos);
  EXPECT_EQ(message(SimPhantomConfig{}), "no error");
}

TEST(SimPhantom, ReadBeforeOpenIsInvalidAndDoesNotBlock) {
  SimPhantom sim(SimPhantomConfig{});
  EXPECT_FALSE(sim.read().valid);
  sim.write(forceCommand({1, 0, 0}));  // ignored
  sim.open();
  const DeviceState s = sim.read();
  EXPECT_TRUE(s.valid);
  EXPECT_EQ(s.timing.tick, 0);
  EXPECT_EQ(sim.truth().periods_integrated, 1);
  EXPECT_EQ(sim.truth().motor_force_n, Eigen::Vector3d::Zero());  // nothing written yet
  EXPECT_EQ(sim.outputMode(), OutputMode::Force);
  EXPECT_EQ(sim.stepsPerTick(), 10);
}

TEST(SimPhantom, FreeHandFollowsAStroke) {
  // 0.08 m at 0.05 m/s, no push, nothing to touch: the pen is dragged by the hand's impedance.
  const HandScript script({HandStroke{{-0.04, 0.0}, {0.04, 0.0}, 0.05, 0.0}});
  const SimPhantomConfig c;
  SimPhantom sim(c, script);
  sim.open();
  const double body_start = script.options().approach_s + script.options().force_ramp_s;
  const double body_end = body_start + 0.08 / 0.05 + script.options().stroke_ramp_s;
  double worst_m = 0.0, lag_sum_m = 0.0;
  int lag_count = 0;
  while (sim.truth().t_s < script.duration() + 0.5) {
    const DeviceState s = sim.read();
    sim.write(DeviceCommand{});
    const SimTruth& t = sim.truth();
    const Eigen::Vector3d error = t.p_world_m - t.hand_target_world.p_m;
    // Transients of the speed-up have died out (grip damping ratio ~0.18) before the window.
    if (t.t_s > body_start + 0.5 && t.t_s < body_end - 0.15) worst_m = std::max(worst_m, error.norm());
    if (t.t_s > body_end - 0.65 && t.t_s < body_end - 0.15) {
      lag_sum_m += error.x();
      ++lag_count;
    }
    EXPECT_LT((s.p_world - t.p_world_m).cwiseAbs().maxCoeff(), 0.5 * c.encoder_resolution_m + 1e-12);
  }
  EXPECT_LT(worst_m, 0.35e-3);
  // Cruising, the pen lags by the mechanism's drag over the grip stiffness.
  const double drag_n = c.friction_n * std::tanh(0.05 / c.friction_velocity_scale_m_per_s) +
                        c.spec.physical_damping_ns_per_m * 0.05;
  EXPECT_NEAR(lag_sum_m / lag_count, -drag_n / c.hand_stiffness_n_per_m, 0.01e-3);
  // After the script the pen rests under the hovering hand.
  EXPECT_LT((sim.truth().p_world_m - sim.truth().hand_target_world.p_m).norm(), 0.1e-3);
}

// While pushing, the hand's normal stiffness drops to a fraction of k_h (force control), so in
// free space the push settles F / (fraction k_h) below the target.
TEST(SimPhantom, PushSagsByForceOverTheHandsPushingStiffnessInFreeSpace) {
  const HandScript script({HandPress{{0.0, 0.0}, 1.5, 5.0}});
  SimPhantomConfig c;
  SimPhantom sim(c, script);
  sim.open();
  while (sim.truth().t_s < 3.5) {  // the weak spring (damping ratio ~0.55) settles within ~1 s
    sim.read();
    sim.write(DeviceCommand{});
  }
  EXPECT_NEAR(sim.truth().p_world_m.z(), -1.5 / (c.hand_push_normal_stiffness_fraction * c.hand_stiffness_n_per_m),
              1e-3);
}

// A move lifts the pen off the surface and pushes it sideways: in free space the pen goes to the
// move's point and, pushing, sags along the push by F over the hand's pushing stiffness, as a press
// sags along the normal (issue 30: the hand that will pinch a box between two pens).
TEST(SimPhantom, AMoveLiftsThePenAndPushesItSideways) {
  const HandScript script({HandMove{{0.0, 0.0, 0.03}, {0.0, 0.0, 0.0}, 0.5}, HandHold{1.0},
                           HandMove{{0.0, 0.0, 0.03}, {-1.5, 0.0, 0.0}, 0.5}, HandHold{3.0}});
  SimPhantomConfig c;
  SimPhantom sim(c, script);
  sim.open();
  while (sim.truth().t_s < 1.4) {  // the lift is done, the push not begun
    sim.read();
    sim.write(DeviceCommand{});
  }
  EXPECT_LT((sim.truth().p_world_m - Eigen::Vector3d(0.0, 0.0, 0.03)).norm(), 0.1e-3);
  EXPECT_FALSE(sim.read().buttons & 1u);  // no push: not pressing
  sim.write(DeviceCommand{});
  while (sim.truth().t_s < 4.9) {  // the last hold ends at 5 s
    sim.read();
    sim.write(DeviceCommand{});
  }
  const double sag = -1.5 / (c.hand_push_normal_stiffness_fraction * c.hand_stiffness_n_per_m);
  EXPECT_NEAR(sim.truth().p_world_m.x(), sag, 1e-3);
  EXPECT_NEAR(sim.truth().p_world_m.z(), 0.03, 0.1e-3);
  EXPECT_TRUE(sim.read().buttons & 1u);  // pushing: button 1
}

TEST(SimPhantom, ReadingsAreEncoderCountsAndVelocityIsTheirDifference) {
  const HandScript script({HandStroke{{-0.02, 0.01}, {0.02, -0.01}, 0.08, 0.0}});
  SimPhantomConfig c;
  c.plane_to_world.linear() = Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 1, 0).normalized()).toRotationMatrix();
  SimPhantom sim(c, script);
  sim.open();
  Eigen::Vector3d prev = sim.read().p_world;
  for (int k = 0; k < 1000; ++k) {
    const DeviceState s = sim.read();
    for (int i = 0; i < 3; ++i) {
      const double counts = s.p_world[i] / c.encoder_resolution_m;
      ASSERT_NEAR(counts, std::round(counts), 1e-6) << "axis " << i;
      ASSERT_LE(std::abs(s.p_world[i] - sim.truth().p_world_m[i]), 0.5 * c.encoder_resolution_m + 1e-12);
    }
    for (int i = 0; i < 3; ++i) ASSERT_NEAR(s.v_world[i], (s.p_world[i] - prev[i]) / kT, 1e-9);
    EXPECT_EQ(s.q_world.coeffs(), Eigen::Quaterniond::Identity().coeffs());
    EXPECT_EQ(s.w_world, Eigen::Vector3d::Zero());
    prev = s.p_world;
  }
}

TEST(SimPhantom, ZeroOrderHoldAppliesTheForceForTheWholeTick) {
  // Free mass: the impulse of one tick is exactly F T.
  const SimPhantomConfig c = freeMassConfig();
  SimPhantom sim(c);
  sim.open();
  sim.read();
  const Eigen::Vector3d f(0.3, -0.2, 0.5);
  const Eigen::Vector3d v0 = sim.truth().v_world_m_per_s;
  sim.write(forceCommand(f));
  sim.read();
  EXPECT_TRUE((massOf(c) * (sim.truth().v_world_m_per_s - v0)).isApprox(f * kT, 1e-12));
  EXPECT_EQ(sim.truth().motor_force_n, f);

  // With the hand and friction acting too, the motor's work over a tick is F . (x_end - x_start):
  // one constant force over the whole tick.
  const HandScript script({HandStroke{{-0.02, 0}, {0.02, 0}, 0.05, 1.0}});
  SimPhantom held(SimPhantomConfig{}, script);
  held.open();
  for (int k = 0; k < 500; ++k) {
    const Eigen::Vector3d x0 = held.truth().p_world_m;
    held.read();
    const Eigen::Vector3d fk(0.1 * std::sin(k * 0.1), 0.2, 0.3 * std::cos(k * 0.07));
    if (k > 0) {
      ASSERT_NEAR(held.truth().motor_work_j, held.truth().motor_force_n.dot(held.truth().p_world_m - x0), 1e-15);
    }
    held.write(forceCommand(fk));
  }
}

TEST(SimPhantom, MotorForceSaturatesAtThePeak) {
  const SimPhantomConfig c = freeMassConfig();
  SimPhantom sim(c);
  sim.open();
  sim.read();
  const Eigen::Vector3d dir = Eigen::Vector3d(1, 1, 0).normalized();
  sim.write(forceCommand(20.0 * dir));
  const Eigen::Vector3d v0 = sim.truth().v_world_m_per_s;
  sim.read();
  EXPECT_TRUE(sim.truth().motor_saturated);
  EXPECT_TRUE(sim.truth().motor_force_n.isApprox(7.9 * dir, 1e-12));
  EXPECT_TRUE((massOf(c) * (sim.truth().v_world_m_per_s - v0)).isApprox(7.9 * dir * kT, 1e-12));
  sim.write(forceCommand(7.0 * dir));
  sim.read();
  EXPECT_FALSE(sim.truth().motor_saturated);
  EXPECT_TRUE(sim.truth().motor_force_n.isApprox(7.0 * dir, 1e-12));
}

TEST(SimPhantom, WatchdogDecaysTheLastForceWhenWritesStop) {
  const SimPhantomConfig c = freeMassConfig();
  SimPhantom sim(c);
  sim.open();
  sim.read();
  const Eigen::Vector3d f(0, 0, 2.0);
  sim.write(forceCommand(f));
  const double expected_gain[] = {1.0, 0.5, 0.25, 0.0, 0.0};
  for (int k = 0; k < 5; ++k) {
    const Eigen::Vector3d v0 = sim.truth().v_world_m_per_s;
    sim.read();  // no write from here on
    EXPECT_TRUE((massOf(c) * (sim.truth().v_world_m_per_s - v0)).isApprox(expected_gain[k] * f * kT, 1e-12) ||
                expected_gain[k] == 0.0)
        << "period " << k;
    EXPECT_EQ(sim.truth().motor_force_n, expected_gain[k] * f) << "period " << k;
    EXPECT_EQ(sim.truth().watchdog_stale_periods, k < 3 ? k : 3);
  }
  // A new write re-arms it at full force.
  sim.write(forceCommand(f));
  sim.read();
  EXPECT_EQ(sim.truth().motor_force_n, f);
}

TEST(SimPhantom, MissedTicksIntegrateTheElapsedTimeUnderTheWatchdog) {
  thx::rt::VirtualClock clock;
  const SimPhantomConfig c = freeMassConfig();
  SimPhantom sim(c, HandScript(), &clock);
  sim.open();
  const Eigen::Vector3d p0 = sim.read().p_world;  // tick 0 at 1 ms
  const Eigen::Vector3d f(5.0, 0, 0);
  sim.write(forceCommand(f));
  const Eigen::Vector3d v0 = sim.truth().v_world_m_per_s;
  const double t0 = sim.truth().t_s;
  clock.advance(3'500'000);  // the servo stalls 3.5 ms: ticks 1, 2, 3 are missed
  const DeviceState s = sim.read();
  EXPECT_EQ(s.timing.missed, 3);
  EXPECT_EQ(s.timing.tick, 4);
  EXPECT_EQ(sim.truth().periods_integrated, 4);
  EXPECT_NEAR(sim.truth().t_s - t0, 4 * kT, 1e-15);
  // The write drives the first period; the watchdog then holds x0.5, x0.25, then zero.
  EXPECT_TRUE((massOf(c) * (sim.truth().v_world_m_per_s - v0)).isApprox(f * kT * 1.75, 1e-12));
  EXPECT_EQ(sim.truth().motor_force_n, Eigen::Vector3d::Zero());
  EXPECT_EQ(sim.truth().watchdog_stale_periods, 3);
  // The reported velocity spans the whole elapsed time since the previous reading.
  EXPECT_GT(s.p_world.x(), p0.x());
  EXPECT_NEAR(s.v_world.x(), (s.p_world.x() - p0.x()) / (4 * kT), 1e-9);
}

TEST(SimPhantom, DisabledOrNonFiniteForcesRenderZero) {
  const SimPhantomConfig c = freeMassConfig();
  SimPhantom sim(c);
  sim.open();
  sim.read();
  DeviceCommand off = forceCommand({1, 2, 3});
  off.forces_enabled = false;
  sim.write(off);
  sim.read();
  EXPECT_EQ(sim.truth().motor_force_n, Eigen::Vector3d::Zero());
  sim.write(forceCommand({std::nan(""), 0, 0}));
  sim.read();
  EXPECT_EQ(sim.truth().motor_force_n, Eigen::Vector3d::Zero());
  EXPECT_EQ(sim.truth().nonfinite_commands, 1);
  EXPECT_TRUE(sim.truth().p_world_m.allFinite());
}

TEST(SimPhantom, NanFaultReportsNanWithValidTrueThenRecovers) {
  SimPhantomConfig c;
  c.faults.nan_from_tick = 5;
  c.faults.nan_ticks = 3;
  const HandScript script({HandStroke{{0, 0}, {0.02, 0}, 0.05, 0.0}});
  SimPhantom sim(c, script);
  sim.open();
  for (int k = 0; k < 12; ++k) {
    const DeviceState s = sim.read();
    const bool faulty = k >= 5 && k < 8;
    EXPECT_TRUE(s.valid);
    EXPECT_EQ(std::isnan(s.p_world.x()) && std::isnan(s.p_world.y()) && std::isnan(s.p_world.z()), faulty) << k;
    EXPECT_EQ(s.v_world.hasNaN(), faulty) << k;
    EXPECT_TRUE(sim.truth().p_world_m.allFinite());  // the device itself is fine
  }
}

TEST(SimPhantom, InvalidFaultHoldsTheLastReadingWithZeroVelocity) {
  SimPhantomConfig c;
  const HandScript script({HandStroke{{0, 0}, {0.05, 0}, 0.1, 0.0}});
  SimPhantom sim(c, script);
  sim.setFaults(SimFaults{-1, 0, 400, 2});
  sim.open();
  DeviceState last_good;
  for (int k = 0; k < 403; ++k) {
    const DeviceState s = sim.read();
    if (k < 400) {
      EXPECT_TRUE(s.valid);
      last_good = s;
    } else if (k < 402) {
      EXPECT_FALSE(s.valid);
      EXPECT_EQ(s.p_world, last_good.p_world);
      EXPECT_EQ(s.v_world, Eigen::Vector3d::Zero());
    } else {
      EXPECT_TRUE(s.valid);
      EXPECT_NE(s.p_world, last_good.p_world);  // the pen kept moving
    }
  }
}

TEST(SimPhantom, ButtonOneWhileTheHandPushes) {
  const HandScript script({HandHold{0.1}, HandPress{{0, 0}, 1.0, 0.5}});
  SimPhantom sim(SimPhantomConfig{}, script);
  sim.open();
  int pressed = 0, released = 0;
  while (sim.truth().t_s < script.duration() + 0.1) {
    const DeviceState s = sim.read();
    EXPECT_EQ(s.buttons, sim.truth().hand_target_world.pressing ? 1u : 0u);
    (s.buttons ? pressed : released)++;
  }
  // Pushing from the start of the ramp-in to the end of the ramp-out: 0.1 + 0.5 + 0.1 s.
  EXPECT_NEAR(pressed, 700, 2);
  EXPECT_GT(released, 0);
}

TEST(SimPhantom, PlanesModeRendersTheCommandedPlane) {
  SimPhantomConfig c;
  c.output_mode = OutputMode::Planes;
  const HandScript script({HandPress{{0, 0}, 1.0, 2.0}});
  SimPhantom sim(c, script);
  EXPECT_EQ(sim.outputMode(), OutputMode::Planes);
  sim.open();
  DeviceCommand cmd;
  cmd.forces_enabled = true;
  cmd.num_planes = 1;
  cmd.planes[0].n_world = Eigen::Vector3d::UnitZ();
  cmd.planes[0].d_m = 0.0;
  cmd.planes[0].k_n_per_m = 500.0;
  cmd.planes[0].b_ns_per_m = 2.0;
  while (sim.truth().t_s < 1.5) {
    sim.read();
    sim.write(cmd);
  }
  // Hand target on the surface, push 1 N, normal stiffness f k_h while pushing: (f k_h + k) z = -F.
  const double k_hand = c.hand_push_normal_stiffness_fraction * c.hand_stiffness_n_per_m;
  EXPECT_NEAR(sim.truth().p_world_m.z(), -1.0 / (500.0 + k_hand), 2e-5);
  EXPECT_NEAR(sim.truth().motor_force_n.z(), 500.0 / (500.0 + k_hand), 0.02);
}

TEST(SimPhantom, LockStepRunsAreBitIdentical) {
  const auto run = [](std::vector<double>& trace) {
    const HandScript script({HandStroke{{-0.02, 0}, {0.02, 0.01}, 0.05, 1.0}});
    SimPhantom sim(SimPhantomConfig{}, script);
    sim.open();
    for (int k = 0; k < 1500; ++k) {
      const DeviceState s = sim.read();
      sim.write(wall(s, 600.0));
      for (int i = 0; i < 3; ++i) trace.insert(trace.end(), {s.p_world[i], s.v_world[i], sim.truth().p_world_m[i]});
      trace.push_back(sim.truth().motor_work_total_j);
    }
  };
  std::vector<double> a, b;
  run(a);
  run(b);
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(double)), 0);
}

TEST(SimPhantom, PacedModeFollowsTheMonotonicClock) {
  // Behaviour only, never a timing bound.
  SimPhantomConfig c;
  c.lockstep = false;
  SimPhantom sim(c);
  sim.open();
  for (int k = 0; k < 5; ++k) {
    const DeviceState s = sim.read();
    EXPECT_GE(s.timing.wake_ns, s.timing.deadline_ns);
    EXPECT_GE(sim.clock().nowNs(), s.timing.deadline_ns);
    sim.write(DeviceCommand{});
  }
}

}  // namespace test_sim_phantom
