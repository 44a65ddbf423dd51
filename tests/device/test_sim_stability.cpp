// docs/design.md §5: "a simulator that cannot go unstable proves nothing about stability". The
// servo side renders a plain wall F = K max(0, -z) n from the device's readings (quantised
// position, no virtual damping) while the hand presses the pen onto it with 1 N. Passivity
// (Colgate): b > K T / 2 + |B|. Lock-step, deterministic.
//
//  - K = 1000 N/m with a light grip (hand mass 0.05 kg), no hand damping, b = 0.002 N·s/m,
//    no friction: K T / 2 = 0.5 >> b. The zero-order hold acts as negative damping of about
//    K T / 2 - b, so the contact oscillation GROWS (and the motors do net positive work).
//  - The same wall with the default hand damping (3 N·s/m) settles.
//  - K = 250 N/m with b = 0.5 N·s/m (K = 2b/T / 4), no hand damping, settles.
//  - The first case with the default Coulomb friction (0.06 N) and hand mass (0.2 kg) also
//    settles: friction removes 4 F_c A per cycle, more than the hold injects at small amplitude
//    A, so only a larger disturbance would start the limit cycle (Diolaiti et al.'s
//    friction-stabilised regime). The demonstration therefore uses friction 0.
//  - Control experiment, b = 0.1 N·s/m (between K dt / 2 = 0.05 at 10 kHz and K T / 2 = 0.5 at
//    1 kHz): the servo's wall grows, the same wall rendered by the device at 10 kHz settles. The
//    sampling rate is what destabilises, not the integrator.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "device/sim_phantom.hpp"

namespace test_sim_stability {

using namespace thx::dev;

namespace {

struct Window {
  double z_min_m = INFINITY, z_max_m = -INFINITY;
  double v_sq_sum = 0.0;
  double motor_work_j = 0.0;
  int ticks = 0;
  double peakToPeakM() const { return z_max_m - z_min_m; }
  double vRms() const { return std::sqrt(v_sq_sum / ticks); }
};

struct WallRun {
  Window early;  // [0.5, 1.0) s: after the pen has landed and the push is in
  Window late;   // [2.5, 3.0) s
  double motor_work_1_to_3_s_j = 0.0;
};

SimPhantomConfig wallConfig(double b_ns_per_m, double hand_damping, double friction_n, double hand_mass_kg) {
  SimPhantomConfig c;
  c.spec.physical_damping_ns_per_m = b_ns_per_m;
  c.hand_damping_ns_per_m = hand_damping;
  c.friction_n = friction_n;
  c.hand_mass_kg = hand_mass_kg;
  return c;
}

// Force mode: the servo renders the wall from readings at 1 kHz. Planes mode: the device renders
// the same wall itself, from the true state at the integration rate.
WallRun pressOnWall(const SimPhantomConfig& c, double k_n_per_m) {
  const HandScript script({HandPress{{0.0, 0.0}, 1.0, 5.0}});  // descends 0.2 s, push in over 0.1 s
  SimPhantom sim(c, script);
  sim.open();
  WallRun run;
  for (int k = 0; k < 3000; ++k) {
    const DeviceState s = sim.read();
    DeviceCommand cmd;
    cmd.forces_enabled = true;
    cmd.num_planes = 1;
    cmd.planes[0].k_n_per_m = k_n_per_m;  // n = +z, d = 0, no plane damping
    cmd.force_world_n = Eigen::Vector3d(0, 0, k_n_per_m * std::max(0.0, -s.p_world.z()));
    sim.write(cmd);
    const SimTruth& t = sim.truth();
    if (t.t_s > 1.0) run.motor_work_1_to_3_s_j += t.motor_work_j;
    Window* w = t.t_s >= 0.5 && t.t_s < 1.0 ? &run.early : t.t_s >= 2.5 ? &run.late : nullptr;
    if (!w) continue;
    w->z_min_m = std::min(w->z_min_m, t.p_world_m.z());
    w->z_max_m = std::max(w->z_max_m, t.p_world_m.z());
    w->v_sq_sum += t.v_world_m_per_s.z() * t.v_world_m_per_s.z();
    w->motor_work_j += t.motor_work_j;
    ++w->ticks;
  }
  return run;
}

void report(const char* name, const WallRun& r) {
  std::printf("%-34s peak-to-peak z %.3g -> %.3g mm, rms v_z %.3g -> %.3g m/s, motor work 1-3 s %+.3g J\n", name,
              r.early.peakToPeakM() * 1e3, r.late.peakToPeakM() * 1e3, r.early.vRms(), r.late.vRms(),
              r.motor_work_1_to_3_s_j);
}

constexpr double kResolution = 2.3e-5;

}  // namespace

TEST(SimStability, StiffWallWithoutDampingOscillatesAndGrows) {
  const SimPhantomConfig c = wallConfig(0.002, 0.0, 0.0, 0.05);
  const double k = 1000.0;
  ASSERT_GT(k, 2.0 * c.spec.physical_damping_ns_per_m / 1e-3 * 100.0);  // far beyond 2b/T = 4 N/m
  const WallRun r = pressOnWall(c, k);
  report("K 1000, hand b 0, b 0.002:", r);
  EXPECT_GT(r.early.peakToPeakM(), 5 * kResolution);  // already oscillating, not noise
  EXPECT_GT(r.late.peakToPeakM(), 5.0 * r.early.peakToPeakM());
  EXPECT_GT(r.late.vRms(), 5.0 * r.early.vRms());
  EXPECT_GT(r.motor_work_1_to_3_s_j, 0.0);  // the sampled wall is active: it pumps energy in
}

TEST(SimStability, SameWallWithHandDampingSettles) {
  const WallRun r = pressOnWall(wallConfig(0.002, 3.0, 0.0, 0.05), 1000.0);
  report("K 1000, hand b 3, b 0.002:", r);
  EXPECT_LT(r.late.peakToPeakM(), 2 * kResolution);  // what is left is encoder-quantisation chatter
  EXPECT_LT(r.late.vRms(), 1e-3);
}

TEST(SimStability, WallWellBelowTwoBOverTSettles) {
  const SimPhantomConfig c = wallConfig(0.5, 0.0, 0.0, 0.05);
  const double k = 250.0;
  ASSERT_LE(k, 0.25 * 2.0 * c.spec.physical_damping_ns_per_m / 1e-3);
  const WallRun r = pressOnWall(c, k);
  report("K 250, hand b 0, b 0.5:", r);
  EXPECT_LT(r.late.peakToPeakM(), 2 * kResolution);
  EXPECT_LT(r.late.peakToPeakM(), 0.1 * r.early.peakToPeakM());
  EXPECT_LT(r.late.vRms(), 1e-3);
}

TEST(SimStability, CoulombFrictionQuenchesASmallOscillationOnTheStiffWall) {
  const WallRun r = pressOnWall(wallConfig(0.005, 0.0, 0.06, 0.2), 1000.0);
  report("K 1000, hand b 0, friction 0.06 N:", r);
  EXPECT_LT(r.late.peakToPeakM(), 2 * kResolution);
  EXPECT_LT(r.late.vRms(), 1e-3);
}

TEST(SimStability, SamplingRateIsWhatDestabilises) {
  SimPhantomConfig c = wallConfig(0.1, 0.0, 0.0, 0.05);
  const WallRun servo = pressOnWall(c, 1000.0);
  c.output_mode = OutputMode::Planes;
  const WallRun device = pressOnWall(c, 1000.0);
  report("K 1000, b 0.1, servo at 1 kHz:", servo);
  report("K 1000, b 0.1, device at 10 kHz:", device);
  EXPECT_GT(servo.late.peakToPeakM(), 5.0 * servo.early.peakToPeakM());
  EXPECT_LT(device.late.peakToPeakM(), 0.5 * device.early.peakToPeakM());
}

}  // namespace test_sim_stability
