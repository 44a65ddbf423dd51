// The external-effect renderer (VRPN Plane / Plane2 / Force_Field / Custom Effect in the servo)
// and the PHANToM clamps that feed it. Lock-step: one render() per tick, no threads.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "server/external_effects.hpp"
#include "server/vrpn_effect_commands.hpp"
#include "tests/support/allocation_counter.hpp"

namespace test_external_effects {

using namespace thx;
using namespace thx::srv;

namespace {

constexpr double kPeriod = 1e-3;
constexpr double kKmax = 1000.0;
// Commands travel as float32 (the wire format): forces agree to float precision, not double.
constexpr double kTol = 1e-6;

EffectLimits limits() {
  EffectLimits l;
  l.max_stiffness_n_per_m = kKmax;
  l.peak_force_n = 7.9;
  l.servo_rate_hz = 1000.0;
  return l;
}

// Floor z = height (normal +z), kspring as given, no damping or friction unless asked.
vrpn::ForcePlane floorPlane(double height, float kspring = 0.5f, std::int32_t rec = 1) {
  vrpn::ForcePlane p;
  p.plane = {0.0f, 0.0f, 1.0f, float(-height)};
  p.kspring = kspring;
  p.kdamp = 0.0f;
  p.fstat = 0.0f;
  p.fdyn = 0.0f;
  p.n_rec_cycles = rec;
  return p;
}

struct Rig {
  ExternalEffects effects;
  ExternalEffectRenderer renderer{kPeriod};
  void push() { renderer.commandSlot().write(effects); }
  ExternalOutput at(double x, double y, double z, Eigen::Vector3d v = Eigen::Vector3d::Zero()) {
    return renderer.render(Eigen::Vector3d(x, y, z), v, true);
  }
};

}  // namespace

TEST(ExternalEffects, NothingCommandedRendersNothing) {
  Rig rig;
  const ExternalOutput o = rig.at(0, 0, -0.01);
  EXPECT_EQ(o.force_world, Eigen::Vector3d::Zero());
  EXPECT_FALSE(o.in_contact);
  EXPECT_FALSE(rig.renderer.anyActive());
}

TEST(ExternalEffects, PlaneSpringPushesOutAlongTheNormal) {
  Rig rig;
  ASSERT_TRUE(applyPlane(rig.effects, floorPlane(0.0, 0.5f), limits()).applied);
  rig.push();
  const ExternalOutput in = rig.at(0.01, 0.02, -0.002);
  EXPECT_TRUE(in.in_contact);
  EXPECT_NEAR(in.force_world.z(), 0.5 * kKmax * 0.002, kTol);
  EXPECT_NEAR(in.force_world.x(), 0.0, 1e-12);
  EXPECT_NEAR(in.scp_world.z(), 0.0, 1e-12);  // the contact point is on the surface
  EXPECT_NEAR(in.scp_world.x(), 0.01, 1e-12);
  const ExternalOutput out = rig.at(0.01, 0.02, 0.001);
  EXPECT_FALSE(out.in_contact);
  EXPECT_EQ(out.force_world, Eigen::Vector3d::Zero());
}

TEST(ExternalEffects, NonUnitNormalIsNormalisedLikeAStockClientSendsIt) {
  // sphere_client sends the raw probe position as the normal: (0, 0, 2) with d = -0.02 is z = 0.01.
  ExternalEffects e;
  vrpn::ForcePlane p = floorPlane(0.0);
  p.plane = {0.0f, 0.0f, 2.0f, -0.02f};
  ASSERT_TRUE(applyPlane(e, p, limits()).applied);
  EXPECT_DOUBLE_EQ(e.planes[0].n[2], 1.0);
  EXPECT_NEAR(e.planes[0].d_m, -0.01, kTol);
}

TEST(ExternalEffects, DampingNeverPullsThePenIn) {
  Rig rig;
  vrpn::ForcePlane p = floorPlane(0.0, 0.5f);
  p.kdamp = 0.005f;  // 5 N·s/m
  applyPlane(rig.effects, p, limits());
  rig.push();
  // Leaving fast at shallow depth: spring 0.5 N, damping -5 N·s/m x 1 m/s = -5 N -> clamped to 0.
  const ExternalOutput o = rig.at(0, 0, -0.001, Eigen::Vector3d(0, 0, 1.0));
  EXPECT_EQ(o.force_world.z(), 0.0);
  // Entering: damping adds.
  const ExternalOutput in = rig.at(0, 0, -0.001, Eigen::Vector3d(0, 0, -0.1));
  EXPECT_NEAR(in.force_world.z(), 0.5 * kKmax * 0.001 + 5.0 * 0.1, kTol);
}

TEST(ExternalEffects, RecoveryKeepsTheDepthThenWalksToTheNewPlaneOverNTicks) {
  Rig rig;
  applyPlane(rig.effects, floorPlane(0.0, 0.5f, 10), limits());
  rig.push();
  const double z = -0.001;  // 1 mm deep in the first plane
  EXPECT_NEAR(rig.at(0, 0, z).force_world.z(), 0.5, kTol);
  // The client raises the plane by 5 mm while the pen is in contact: no jump to 3 N.
  applyPlane(rig.effects, floorPlane(0.005, 0.5f, 10), limits());
  rig.push();
  std::vector<double> f;
  for (int k = 0; k < 12; ++k) f.push_back(rig.at(0, 0, z).force_world.z());
  // Tick 1 already takes the first step of 10: 1 mm + 0.5 mm.
  EXPECT_NEAR(f[0], 0.5 * kKmax * 0.0015, kTol);
  for (int k = 1; k < 10; ++k) EXPECT_NEAR(f[std::size_t(k)] - f[std::size_t(k - 1)], 0.25, kTol) << k;
  EXPECT_NEAR(f[9], 0.5 * kKmax * 0.006, kTol);
  EXPECT_NEAR(f[11], f[9], 1e-12);
}

TEST(ExternalEffects, PlaneChangeOutOfContactOrWithOneRecoveryCycleIsImmediate) {
  Rig rig;
  applyPlane(rig.effects, floorPlane(0.0, 0.5f, 10), limits());
  rig.push();
  rig.at(0, 0, 0.01);  // free
  applyPlane(rig.effects, floorPlane(0.02, 0.5f, 10), limits());
  rig.push();
  EXPECT_NEAR(rig.at(0, 0, 0.01).force_world.z(), 0.5 * kKmax * 0.01, kTol);  // full depth at once

  Rig one;
  applyPlane(one.effects, floorPlane(0.0, 0.5f, 1), limits());
  one.push();
  one.at(0, 0, -0.001);
  applyPlane(one.effects, floorPlane(0.005, 0.5f, 1), limits());
  one.push();
  EXPECT_NEAR(one.at(0, 0, -0.001).force_world.z(), 0.5 * kKmax * 0.006, kTol);
}

TEST(ExternalEffects, FrictionSticksThenSlipsAtTheDynamicCoefficient) {
  Rig rig;
  vrpn::ForcePlane p = floorPlane(0.0, 1.0f);
  p.fstat = 0.5f;
  p.fdyn = 0.3f;
  applyPlane(rig.effects, p, limits());
  rig.push();
  const double z = -0.002;  // F_n = 2 N
  rig.at(0, 0, z);          // contact starts at x = 0: the stick point
  // 0.5 mm sideways: 0.5 N tangential, below mu_s F_n = 1 N: stuck, pulling back.
  ExternalOutput o = rig.at(0.0005, 0, z);
  EXPECT_NEAR(o.force_world.x(), -0.5, kTol);
  EXPECT_NEAR(o.force_world.z(), 2.0, kTol);
  // 3 mm: 3 N would exceed 1 N: slips, drags at mu_d F_n = 0.6 N.
  o = rig.at(0.003, 0, z);
  EXPECT_NEAR(o.force_world.x(), -0.6, kTol);
  // The stick point moved along: stepping back 0.1 mm reduces the drag spring-wise.
  o = rig.at(0.0029, 0, z);
  EXPECT_NEAR(o.force_world.x(), -0.5, kTol);
}

TEST(ExternalEffects, ForceFieldActsInsideItsRadiusOnly) {
  Rig rig;
  vrpn::ForceField f;
  f.origin = {0.0f, 0.0f, 0.0f};
  f.force = {0.0f, 0.5f, 0.0f};
  f.jacobian[0][0] = -100.0f;  // a spring toward x = 0
  f.radius = 0.05f;
  ASSERT_TRUE(applyField(rig.effects, f, limits()).applied);
  rig.push();
  const ExternalOutput in = rig.at(0.01, 0, 0);
  EXPECT_NEAR(in.force_world.x(), -1.0, 1e-6);
  EXPECT_NEAR(in.force_world.y(), 0.5, 1e-6);
  EXPECT_EQ(rig.at(0.06, 0, 0).force_world, Eigen::Vector3d::Zero());
  // All zeros is "stop".
  ASSERT_TRUE(applyField(rig.effects, vrpn::ForceField{}, limits()).applied);
  rig.push();
  EXPECT_EQ(rig.at(0.01, 0, 0).force_world, Eigen::Vector3d::Zero());
  EXPECT_FALSE(rig.effects.field.on);
}

TEST(ExternalEffects, BuzzRunsForItsDurationAlongItsDirection) {
  Rig rig;
  vrpn::ForceCustomEffect b;
  b.effect_id = 0;
  b.params = {1.0f, 250.0f, 0.01f, 1.0f, 0.0f, 0.0f};  // 1 N, 250 Hz, 10 ms, along +x
  ASSERT_TRUE(applyCustomEffect(rig.effects, b, limits()).applied);
  rig.push();
  double peak = 0.0;
  for (int k = 0; k < 10; ++k) {
    const ExternalOutput o = rig.at(0, 0, 0.1);
    EXPECT_NEAR(o.force_world.x(), std::sin(2.0 * std::numbers::pi * 250.0 * k * kPeriod), kTol) << k;
    EXPECT_EQ(o.force_world.y(), 0.0);
    peak = std::max(peak, std::abs(o.force_world.x()));
  }
  EXPECT_NEAR(peak, 1.0, kTol);
  for (int k = 0; k < 5; ++k) EXPECT_EQ(rig.at(0, 0, 0.1).force_world, Eigen::Vector3d::Zero());
}

TEST(ExternalEffects, AdhesionHoldsThePenUntilItIsLiftedPastTheSnapDistance) {
  Rig rig;
  applyPlane(rig.effects, floorPlane(0.0, 0.5f), limits());
  vrpn::ForcePlane2 s;
  s.k_adhesion_normal = 0.2f;  // 200 N/m
  applyPlane2(rig.effects, s, limits());
  rig.push();
  EXPECT_EQ(rig.at(0, 0, 0.0005).force_world, Eigen::Vector3d::Zero());  // never touched: no pull
  rig.at(0, 0, -0.001);                                                    // contact
  EXPECT_NEAR(rig.at(0, 0, 0.0005).force_world.z(), -200.0 * 0.0005, kTol);
  EXPECT_EQ(rig.at(0, 0, 0.0015).force_world, Eigen::Vector3d::Zero());   // snapped off
  EXPECT_EQ(rig.at(0, 0, 0.0005).force_world, Eigen::Vector3d::Zero());   // and stays off
}

TEST(ExternalEffects, SurfaceTextureRaisesPlaneZeroSinusoidally) {
  Rig rig;
  applyPlane(rig.effects, floorPlane(0.0, 1.0f), limits());
  vrpn::ForcePlane2 s;
  s.tex_amp = 0.001f;
  s.tex_wavelength = 0.004f;
  applyPlane2(rig.effects, s, limits());
  rig.push();
  // Sampled over a wavelength square, the force (k x (raise - z)) spans k x 2 x amplitude.
  double lo = 1e9, hi = -1e9;
  for (int i = 0; i < 40; ++i)
    for (int j = 0; j < 40; ++j) {
      const double fz = rig.at(i * 1e-4, j * 1e-4, -0.0015).force_world.z();
      lo = std::min(lo, fz);
      hi = std::max(hi, fz);
    }
  EXPECT_NEAR(hi, kKmax * 0.0025, 0.05);
  EXPECT_NEAR(lo, kKmax * 0.0005, 0.05);
}

TEST(ExternalEffects, AnInvalidReadingRendersNothingAndForgetsContacts) {
  Rig rig;
  vrpn::ForcePlane p = floorPlane(0.0, 1.0f);
  p.fstat = 0.5f;
  p.fdyn = 0.3f;
  applyPlane(rig.effects, p, limits());
  rig.push();
  rig.at(0, 0, -0.002);
  const ExternalOutput bad = rig.renderer.render(Eigen::Vector3d(0.0005, 0, -0.002), Eigen::Vector3d::Zero(), false);
  EXPECT_EQ(bad.force_world, Eigen::Vector3d::Zero());
  // The stick point was forgotten: contact restarts where the pen is now (no tangential pull).
  EXPECT_NEAR(rig.at(0.0005, 0, -0.002).force_world.x(), 0.0, 1e-12);
}

TEST(ExternalEffects, ResetTurnsEverythingOff) {
  Rig rig;
  applyPlane(rig.effects, floorPlane(0.0), limits());
  vrpn::ForceField f;
  f.force = {1.0f, 0.0f, 0.0f};
  f.radius = 1.0f;
  applyField(rig.effects, f, limits());
  rig.push();
  EXPECT_GT(rig.at(0, 0, -0.001).force_world.norm(), 0.0);
  EXPECT_TRUE(rig.renderer.anyActive());
  resetEffects(rig.effects);
  rig.push();
  EXPECT_EQ(rig.at(0, 0, -0.001).force_world, Eigen::Vector3d::Zero());
  EXPECT_FALSE(rig.renderer.anyActive());
}

TEST(ExternalEffects, RenderingAllocatesNothing) {
  Rig rig;
  for (int i = 0; i < kMaxExternalPlanes; ++i) {
    vrpn::ForcePlane p = floorPlane(0.001 * i, 0.3f, 5);
    p.plane_index = i;
    p.fstat = 0.4f;
    p.fdyn = 0.2f;
    applyPlane(rig.effects, p, limits());
  }
  vrpn::ForcePlane2 s;
  s.tex_amp = 0.0005f;
  s.tex_wavelength = 0.003f;
  s.buzz_amp = 0.0001f;
  s.buzz_freq = 100.0f;
  s.k_adhesion_normal = 0.1f;
  applyPlane2(rig.effects, s, limits());
  vrpn::ForceField f;
  f.force = {0.1f, 0.0f, 0.0f};
  f.radius = 1.0f;
  applyField(rig.effects, f, limits());
  vrpn::ForceCustomEffect b;
  b.params = {0.5f, 100.0f, 10.0f};
  applyCustomEffect(rig.effects, b, limits());
  rig.push();
  const long before = test::g_allocations.load();
  for (int k = 0; k < 5000; ++k) {
    if (k % 500 == 0) rig.push();  // new commands arrive through the slot
    const double z = -0.003 + 0.004 * std::sin(k * 0.01);
    const ExternalOutput o = rig.at(0.001 * std::cos(k * 0.003), 0.0, z);
    ASSERT_TRUE(o.force_world.allFinite());
  }
  EXPECT_EQ(test::g_allocations.load() - before, 0);
}

// ---- The clamps (docs/vrpn.md §9) ------------------------------------------------------------

TEST(VrpnEffectCommands, PlaneParametersAreClampedLikeVrpnPhantom) {
  ExternalEffects e;
  vrpn::ForcePlane p = floorPlane(0.0, 0.0f);
  p.kdamp = 0.1f;
  p.fstat = 1.5f;
  p.fdyn = 2.0f;
  p.n_rec_cycles = -3;
  ASSERT_TRUE(applyPlane(e, p, limits()).applied);
  EXPECT_DOUBLE_EQ(e.planes[0].k_n_per_m, 0.001 * kKmax);
  EXPECT_DOUBLE_EQ(e.planes[0].b_ns_per_m, 5.0);  // 0.005 N·s/mm
  EXPECT_DOUBLE_EQ(e.planes[0].mu_static, 1.0);
  EXPECT_DOUBLE_EQ(e.planes[0].mu_dynamic, 0.0);  // fdyn > fstat -> 0
  EXPECT_EQ(e.planes[0].recovery_ticks, 1);
  p.kspring = 7.0f;
  p.fdyn = 0.4f;
  p.fstat = 0.6f;
  p.kdamp = -1.0f;
  p.n_rec_cycles = 1'000'000;
  ASSERT_TRUE(applyPlane(e, p, limits()).applied);
  EXPECT_DOUBLE_EQ(e.planes[0].k_n_per_m, kKmax);
  EXPECT_DOUBLE_EQ(e.planes[0].b_ns_per_m, 0.0);
  EXPECT_NEAR(e.planes[0].mu_dynamic, 0.4, 1e-6);
  EXPECT_EQ(e.planes[0].recovery_ticks, 1000);
}

TEST(VrpnEffectCommands, BadPlanesAreRefusedWithAReasonAndChangeNothing) {
  ExternalEffects e;
  ASSERT_TRUE(applyPlane(e, floorPlane(0.0), limits()).applied);
  const ExternalEffects before = e;
  vrpn::ForcePlane p = floorPlane(0.01);
  p.plane_index = 4;
  CommandVerdict v = applyPlane(e, p, limits());
  EXPECT_FALSE(v.applied);
  EXPECT_NE(v.problem.find("plane_index = 4"), std::string::npos) << v.problem;
  p.plane_index = 0;
  p.plane[3] = std::nanf("");
  v = applyPlane(e, p, limits());
  EXPECT_FALSE(v.applied);
  EXPECT_NE(v.problem.find("not finite"), std::string::npos) << v.problem;
  EXPECT_EQ(e.planes[0].version, before.planes[0].version);
  EXPECT_EQ(e.planes[0].d_m, before.planes[0].d_m);
}

TEST(VrpnEffectCommands, ZeroNormalTurnsThePlaneOffAndRepeatsAreNoOps) {
  ExternalEffects e;
  ASSERT_TRUE(applyPlane(e, floorPlane(0.0), limits()).applied);
  const std::uint32_t v1 = e.planes[0].version;
  EXPECT_FALSE(applyPlane(e, floorPlane(0.0), limits()).applied);  // sendSurface at 30 Hz, unchanged
  EXPECT_EQ(e.planes[0].version, v1);
  ASSERT_TRUE(applyPlane(e, vrpn::stopSurface(floorPlane(0.0)), limits()).applied);
  EXPECT_FALSE(e.planes[0].on);
  EXPECT_GT(e.planes[0].version, v1);
}

TEST(VrpnEffectCommands, FieldsAreBoundedByThePeakForceAndMaximumStiffness) {
  ExternalEffects e;
  vrpn::ForceField f;
  f.force = {30.0f, 40.0f, 0.0f};  // 50 N
  f.jacobian[0][0] = -30000.0f;
  f.radius = 0.1f;
  const CommandVerdict v = applyField(e, f, limits());
  ASSERT_TRUE(v.applied);
  EXPECT_FALSE(v.note.empty());
  const double fn = std::hypot(e.field.force_n[0], e.field.force_n[1]);
  EXPECT_NEAR(fn, 7.9, kTol);
  EXPECT_NEAR(e.field.jacobian_n_per_m[0][0], -kKmax, kTol);
  f.radius = std::numeric_limits<float>::infinity();
  EXPECT_FALSE(applyField(e, f, limits()).problem.empty());
}

TEST(VrpnEffectCommands, CustomEffectsOtherThanBuzzAreRefused) {
  ExternalEffects e;
  vrpn::ForceCustomEffect c;
  c.effect_id = 5;
  c.params = {1.0f, 2.0f, 3.0f};
  CommandVerdict v = applyCustomEffect(e, c, limits());
  EXPECT_NE(v.problem.find("effect_id = 5"), std::string::npos) << v.problem;
  c.effect_id = 0;
  c.params = {1.0f};
  v = applyCustomEffect(e, c, limits());
  EXPECT_NE(v.problem.find("params = 1"), std::string::npos) << v.problem;
  c.params = {100.0f, 5000.0f, 1000.0f, 0.0f, 3.0f, 4.0f};
  ASSERT_TRUE(applyCustomEffect(e, c, limits()).applied);
  EXPECT_DOUBLE_EQ(e.buzz.amplitude_n, 7.9);
  EXPECT_DOUBLE_EQ(e.buzz.frequency_hz, 500.0);
  EXPECT_DOUBLE_EQ(e.buzz.duration_s, 60.0);
  EXPECT_NEAR(e.buzz.direction[1], 0.6, 1e-12);
  c.effect_id = vrpn::ForceCustomEffect::kStopEffect;
  c.params.clear();
  ASSERT_TRUE(applyCustomEffect(e, c, limits()).applied);
  EXPECT_FALSE(e.buzz.on);
}

}  // namespace test_external_effects
