// The safety stage, rule by rule and in combination: finite check, engage procedure and ramp,
// peak clamp, continuous-force budget (timed against the EMA math), force-rate limit, shutdown,
// disengage; a seeded fuzz for the peak bound; no allocation in the tick.
#include <gtest/gtest.h>

#include "tests/support/allocation_counter.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <new>
#include <random>
#include <string>

#include "device/device_specs.hpp"
#include "server/safety.hpp"

namespace test_safety {

using namespace thx;
using srv::SafetyConfig;
using srv::SafetyStage;
using srv::SafetyState;
using Eigen::Vector3d;



namespace {

constexpr double kT = 1e-3;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// PHANToM Desktop as in device/device_specs.cpp (written out so these numbers are the test's own).
dev::DeviceSpec desktop() { return dev::phantomDesktopSpec(); }

// Desktop limits with every rule but the one under test out of the way.
SafetyConfig isolated() {
  SafetyConfig c = SafetyConfig::fromSpec(desktop(), kT);
  c.continuous_force_n = c.peak_force_n;  // the average of |F|^2 can never exceed peak^2
  c.max_force_rate_n_per_s = 1e12;
  c.engage_ticks = 1;
  c.ramp_in_s = 0.0;
  return c;
}

void engage(SafetyStage& s) {
  for (int i = 0; i < 10000 && s.state() != SafetyState::Engaged; ++i) s.apply(Vector3d::Zero());
  ASSERT_EQ(s.state(), SafetyState::Engaged);
}

double smoothstep(double p) { return p * p * (3.0 - 2.0 * p); }

std::string rejection(const SafetyConfig& c) {
  try {
    SafetyStage stage(c);
  } catch (const thx::Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(SafetyConfig, FromSpecTakesTheDeviceLimits) {
  const SafetyConfig c = SafetyConfig::fromSpec(desktop(), kT);
  EXPECT_DOUBLE_EQ(c.peak_force_n, 7.9);
  EXPECT_DOUBLE_EQ(c.continuous_force_n, 1.185);
  EXPECT_DOUBLE_EQ(c.max_force_rate_n_per_s, 5000.0);  // 2.5 x 1000 N/m x 2 m/s
  EXPECT_DOUBLE_EQ(c.period_s, kT);
  EXPECT_DOUBLE_EQ(c.engage_threshold_n, 0.2);
  EXPECT_EQ(c.engage_ticks, 3);
  EXPECT_DOUBLE_EQ(c.ramp_in_s, 0.5);
  EXPECT_DOUBLE_EQ(c.ramp_out_s, 0.2);
  EXPECT_DOUBLE_EQ(c.thermal_time_constant_s, 5.0);

  dev::DeviceSpec no_stiffness = desktop();
  no_stiffness.max_stiffness_n_per_m = 0.0;
  EXPECT_DOUBLE_EQ(SafetyConfig::fromSpec(no_stiffness, kT).max_force_rate_n_per_s, 5000.0);
}

TEST(SafetyConfig, RejectsBadFieldsNamingFieldValueAndExpectation) {
  dev::DeviceSpec spec = desktop();
  spec.continuous_force_n = 0.0;
  try {
    SafetyConfig::fromSpec(spec, kT);
    FAIL() << "expected a rejection";
  } catch (const thx::Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("phantom_desktop"), std::string::npos) << what;
    EXPECT_NE(what.find("continuous_force_n = 0"), std::string::npos) << what;
    EXPECT_NE(what.find("expected"), std::string::npos) << what;
  }

  struct Case {
    const char* field;
    void (*spoil)(SafetyConfig&);
  };
  const Case cases[] = {
      {"period_s", [](SafetyConfig& c) { c.period_s = 0.0; }},
      {"peak_force_n", [](SafetyConfig& c) { c.peak_force_n = kNaN; }},
      {"continuous_force_n", [](SafetyConfig& c) { c.continuous_force_n = 8.0; }},
      {"thermal_time_constant_s", [](SafetyConfig& c) { c.thermal_time_constant_s = -1.0; }},
      {"continuous_release_fraction", [](SafetyConfig& c) { c.continuous_release_fraction = 1.5; }},
      {"max_force_rate_n_per_s", [](SafetyConfig& c) { c.max_force_rate_n_per_s = kInf; }},
      {"engage_threshold_n", [](SafetyConfig& c) { c.engage_threshold_n = 0.0; }},
      {"engage_ticks", [](SafetyConfig& c) { c.engage_ticks = 0; }},
      {"ramp_in_s", [](SafetyConfig& c) { c.ramp_in_s = -0.1; }},
      {"ramp_out_s", [](SafetyConfig& c) { c.ramp_out_s = kNaN; }},
  };
  for (const Case& k : cases) {
    SafetyConfig c = SafetyConfig::fromSpec(desktop(), kT);
    k.spoil(c);
    const std::string what = rejection(c);
    EXPECT_NE(what.find(k.field), std::string::npos) << k.field << ": '" << what << "'";
  }
}

TEST(Safety, StartsDisengagedAndEngagesOnlyAfterSmallForceForNTicksThenRamps) {
  SafetyStage s(SafetyConfig::fromSpec(desktop(), kT));
  EXPECT_EQ(s.state(), SafetyState::Disengaged);
  const Vector3d big(1.0, 0.0, 0.0);
  for (int i = 0; i < 100; ++i) {
    EXPECT_EQ(s.apply(big), Vector3d::Zero());
    EXPECT_TRUE(s.flags() & srv::kSafetyDisengaged);
  }
  // Small, small, large: the count starts again.
  const Vector3d small(0.1, 0.05, 0.0);
  s.apply(small);
  s.apply(small);
  s.apply(Vector3d(0.0, 0.0, 0.25));
  s.apply(small);
  s.apply(small);
  EXPECT_EQ(s.state(), SafetyState::Disengaged);
  EXPECT_EQ(s.apply(small), Vector3d::Zero());  // third consecutive small tick: still zero out
  EXPECT_EQ(s.state(), SafetyState::RampingIn);

  // Ramp: 0.5 s = 500 ticks of output = gain x request, gain = smoothstep(j / 500).
  const Vector3d request(0.0, 3.0, -1.0);
  double last_gain = 0.0;
  for (int j = 1; j <= 500; ++j) {
    const Vector3d out = s.apply(request);
    const double gain = smoothstep(j / 500.0);
    EXPECT_NEAR(s.gain(), gain, 1e-15) << j;
    EXPECT_LT((out - gain * request).norm(), 1e-12) << j;
    EXPECT_GE(s.gain(), last_gain);
    EXPECT_EQ(bool(s.flags() & srv::kSafetyEngaging), j < 500) << j;
    last_gain = s.gain();
  }
  EXPECT_EQ(s.state(), SafetyState::Engaged);
  EXPECT_EQ(s.gain(), 1.0);
  EXPECT_EQ(s.apply(request), request);
  EXPECT_EQ(s.flags(), 0u);
}

TEST(Safety, LinearRampIsLinear) {
  SafetyConfig c = SafetyConfig::fromSpec(desktop(), kT);
  c.ramp_shape = srv::RampShape::Linear;
  SafetyStage s(c);
  for (int i = 0; i < 3; ++i) s.apply(Vector3d::Zero());
  for (int j = 1; j <= 500; ++j) {
    s.apply(Vector3d(1.0, 0.0, 0.0));
    EXPECT_NEAR(s.gain(), j / 500.0, 1e-15);
  }
}

TEST(Safety, NonFiniteOutputsZeroDisengagesAndNeedsTheFullEngageProcedure) {
  for (const double bad : {kNaN, kInf, -kInf}) {
    SafetyStage s(SafetyConfig::fromSpec(desktop(), kT));
    for (int i = 0; i < 3; ++i) s.apply(Vector3d::Zero());
    for (int j = 0; j < 500; ++j) s.apply(Vector3d(0.5, 0.0, 0.0));
    ASSERT_EQ(s.state(), SafetyState::Engaged);
    ASSERT_EQ(s.apply(Vector3d(0.5, 0.0, 0.0)), Vector3d(0.5, 0.0, 0.0));

    EXPECT_EQ(s.apply(Vector3d(0.5, bad, 0.0)), Vector3d::Zero());
    EXPECT_TRUE(s.flags() & srv::kSafetyNonFinite);
    EXPECT_TRUE(s.flags() & srv::kSafetyDisengaged);
    EXPECT_EQ(s.state(), SafetyState::Disengaged);
    EXPECT_EQ(s.counters().non_finite, 1u);
    EXPECT_EQ(s.counters().disengage_events, 1u);

    // A finite but large request does not bring the force back.
    for (int i = 0; i < 50; ++i) EXPECT_EQ(s.apply(Vector3d(0.5, 0.0, 0.0)), Vector3d::Zero());
    // Small for 3 ticks (output still zero), then the ramp from zero again.
    for (int i = 0; i < 3; ++i) EXPECT_EQ(s.apply(Vector3d(0.1, 0.0, 0.0)), Vector3d::Zero());
    const Vector3d first = s.apply(Vector3d(0.5, 0.0, 0.0));
    EXPECT_GT(first.x(), 0.0);
    EXPECT_NEAR(first.x(), 0.5 * smoothstep(1.0 / 500.0), 1e-15);
  }
}

TEST(Safety, DisengageOutputsZeroAtOnce) {
  SafetyStage s(isolated());
  engage(s);
  EXPECT_EQ(s.apply(Vector3d(3.0, 0.0, 0.0)), Vector3d(3.0, 0.0, 0.0));
  s.disengage();
  EXPECT_EQ(s.apply(Vector3d(3.0, 0.0, 0.0)), Vector3d::Zero());  // no rate-limited descent
  EXPECT_EQ(s.state(), SafetyState::Disengaged);
  EXPECT_EQ(s.counters().disengage_events, 1u);
  s.disengage();  // already disengaged: not a new event
  EXPECT_EQ(s.counters().disengage_events, 1u);
}

TEST(Safety, PeakClampKeepsTheDirection) {
  SafetyStage s(isolated());
  engage(s);
  const Vector3d under(3.0, -4.0, 2.0);
  EXPECT_EQ(s.apply(under), under);
  EXPECT_FALSE(s.flags() & srv::kSafetyPeakClamped);

  for (const Vector3d& request :
       {Vector3d(30.0, -40.0, 10.0), Vector3d(1e308, 1e308, -1e308), Vector3d(0.0, 0.0, -1e300),
        Vector3d(8.0, 0.0, 0.0)}) {
    const Vector3d out = s.apply(request);
    EXPECT_TRUE(s.flags() & srv::kSafetyPeakClamped);
    EXPECT_NEAR(out.norm(), 7.9, 1e-12);
    const Vector3d direction = request / request.cwiseAbs().maxCoeff();
    EXPECT_LT((out.normalized() - direction.normalized()).norm(), 1e-12);
  }
}

TEST(Safety, AfterARiddenThroughGapTheRateLimitCountsFromTheHeldForce) {
  SafetyConfig c = isolated();
  c.max_force_rate_n_per_s = 5000.0;  // 5 N per tick
  SafetyStage s(c);
  engage(s);
  s.apply(Vector3d(5.0, 0.0, 0.0));
  EXPECT_NEAR(s.apply(Vector3d(7.0, 0.0, 0.0)).x(), 7.0, 1e-12);
  // The device's watchdog dropped the force to zero over the gap: back to 7 N in two steps.
  s.restartRateLimitFrom(0.0);
  EXPECT_NEAR(s.apply(Vector3d(7.0, 0.0, 0.0)).x(), 5.0, 1e-12);
  EXPECT_TRUE(s.flags() & srv::kSafetyRateLimited);
  EXPECT_NEAR(s.apply(Vector3d(7.0, 0.0, 0.0)).x(), 7.0, 1e-12);
  // It still held half (one missed period): 3.5 N -> 7 N is inside one step.
  s.restartRateLimitFrom(0.5);
  EXPECT_NEAR(s.apply(Vector3d(7.0, 0.0, 0.0)).x(), 7.0, 1e-12);
  EXPECT_FALSE(s.flags() & srv::kSafetyRateLimited);
  EXPECT_EQ(s.state(), SafetyState::Engaged) << "a gap ridden through is no disengagement";
  EXPECT_EQ(s.counters().disengage_events, 0u);
  // Out-of-range and NaN gains are clamped, never raise the reference.
  s.restartRateLimitFrom(2.0);
  EXPECT_NEAR(s.lastOutput().x(), 7.0, 1e-12);
  s.restartRateLimitFrom(kNaN);
  EXPECT_EQ(s.lastOutput().x(), 0.0);
}

TEST(Safety, RateLimitBoundsEveryStep) {
  SafetyConfig c = isolated();
  c.max_force_rate_n_per_s = 5000.0;  // 5 N per tick
  SafetyStage s(c);
  engage(s);
  const double step = 5000.0 * kT;

  Vector3d out = s.apply(Vector3d(7.9, 0.0, 0.0));
  EXPECT_NEAR(out.x(), 5.0, 1e-12);
  EXPECT_TRUE(s.flags() & srv::kSafetyRateLimited);
  EXPECT_NEAR(s.apply(Vector3d(7.9, 0.0, 0.0)).x(), 7.9, 1e-12);
  EXPECT_FALSE(s.flags() & srv::kSafetyRateLimited);

  // Full reversal: 7.9 -> -7.9 in steps of 5 N.
  const double expected[] = {2.9, -2.1, -7.1, -7.9};
  for (const double x : expected) EXPECT_NEAR(s.apply(Vector3d(-7.9, 0.0, 0.0)).x(), x, 1e-12);

  // Sideways: the step points along the requested change.
  Vector3d prev = s.lastOutput();
  const Vector3d target(0.0, 7.9, 0.0);
  out = s.apply(target);
  EXPECT_NEAR((out - prev).norm(), step, 1e-12);
  EXPECT_LT(((out - prev).normalized() - (target - prev).normalized()).norm(), 1e-12);
  for (int i = 0; i < 10; ++i) {
    prev = s.lastOutput();
    out = s.apply(target);
    EXPECT_LE((out - prev).norm(), step + 1e-12);
  }
  EXPECT_LT((out - target).norm(), 1e-12);
}

// The continuous budget engages when the EMA of |F|^2 crosses Fc^2 and releases when it is back
// to 0.81 Fc^2; both moments follow e_n = e_0 q^n + F^2 (1 - q^n), q = exp(-T / tau).
TEST(Safety, ContinuousBudgetEngagesAndReleasesOnTheEmaSchedule) {
  SafetyConfig c = SafetyConfig::fromSpec(desktop(), kT);
  c.max_force_rate_n_per_s = 1e12;
  c.engage_ticks = 1;
  c.ramp_in_s = 0.0;
  SafetyStage s(c);
  engage(s);
  ASSERT_EQ(s.meanSquareForceN2(), 0.0);

  const double tau = c.thermal_time_constant_s;
  const double fc = c.continuous_force_n;
  const double f = 3.0;
  const double q = std::exp(-kT / tau);
  double e = 0.0;
  int crossing = 0;  // ticks of full force before the average first exceeds Fc^2
  while (e <= fc * fc) {
    e = q * e + (1.0 - q) * f * f;
    ++crossing;
  }
  // The continuous-time answer, -tau ln(1 - Fc^2/F^2) = 0.848 s, to within a tick.
  EXPECT_NEAR(crossing * kT, -tau * std::log(1.0 - fc * fc / (f * f)), kT);

  const Vector3d request(0.0, 0.0, f);
  for (int n = 1; n <= crossing; ++n) {
    ASSERT_EQ(s.apply(request), request) << "peaks are allowed while the budget lasts, tick " << n;
    // The budget runs out on the crossing tick only: the servo's FAULT_FORCE_BUDGET.
    ASSERT_EQ(bool(s.flags() & srv::kSafetyBudgetExhausted), n == crossing) << n;
  }
  EXPECT_TRUE(s.continuousLimitActive());
  EXPECT_NEAR(s.meanSquareForceN2(), e, 1e-12 * e);

  // Limited to Fc from the next tick on, for as long as the hand keeps asking for more.
  for (int n = 0; n < 2000; ++n) {
    const Vector3d out = s.apply(request);
    ASSERT_NEAR(out.z(), fc, 1e-12);
    ASSERT_TRUE(s.flags() & srv::kSafetyContinuousLimited);
    ASSERT_FALSE(s.flags() & srv::kSafetyBudgetExhausted) << "once per episode";
    e = q * e + (1.0 - q) * fc * fc;
  }
  EXPECT_TRUE(s.continuousLimitActive());
  EXPECT_NEAR(s.meanSquareForceN2(), e, 1e-9 * e);

  // Let go: released once the average has cooled to 0.81 Fc^2.
  const double release = c.continuous_release_fraction * fc * fc;
  int cooling = 0;
  while (e > release) {
    e *= q;
    ++cooling;
  }
  EXPECT_NEAR(cooling * kT, tau * std::log(s.meanSquareForceN2() / release), kT);
  for (int n = 1; n < cooling; ++n) {
    s.apply(Vector3d::Zero());
    ASSERT_TRUE(s.continuousLimitActive()) << n;
  }
  s.apply(Vector3d::Zero());
  EXPECT_FALSE(s.continuousLimitActive());
  EXPECT_EQ(s.apply(request), request);  // the full force is back
}

TEST(Safety, ShutdownRampsToExactlyZeroInRampOutTime) {
  for (const srv::RampShape shape : {srv::RampShape::Smooth, srv::RampShape::Linear}) {
    SafetyConfig c = isolated();
    c.ramp_shape = shape;
    SafetyStage s(c);
    engage(s);
    const Vector3d request(2.0, -1.0, 0.5);
    ASSERT_EQ(s.apply(request), request);
    s.requestShutdown();
    EXPECT_FALSE(s.shutdownComplete());
    for (int j = 1; j < 200; ++j) {  // ramp_out_s = 0.2 s = 200 ticks
      const Vector3d out = s.apply(request);
      const double p = (200 - j) / 200.0;
      const double gain = shape == srv::RampShape::Smooth ? smoothstep(p) : p;
      ASSERT_LT((out - gain * request).norm(), 1e-12) << j;
      ASSERT_GT(out.norm(), 0.0) << j;
      ASSERT_TRUE(s.flags() & srv::kSafetyRampingOut);
      ASSERT_FALSE(s.shutdownComplete());
    }
    EXPECT_EQ(s.apply(request), Vector3d::Zero());
    EXPECT_TRUE(s.shutdownComplete());
    EXPECT_EQ(s.gain(), 0.0);
    for (int i = 0; i < 10; ++i) {
      EXPECT_EQ(s.apply(Vector3d(7.0, 0.0, 0.0)), Vector3d::Zero());
      EXPECT_TRUE(s.flags() & srv::kSafetyShutDown);
    }
  }
}

TEST(Safety, ShutdownDuringRampInNeverRaisesTheGain) {
  SafetyStage s(SafetyConfig::fromSpec(desktop(), kT));
  for (int i = 0; i < 3; ++i) s.apply(Vector3d::Zero());
  for (int j = 0; j < 300; ++j) s.apply(Vector3d(1.0, 0.0, 0.0));
  const double gain_at_request = s.gain();
  s.requestShutdown();
  double last = gain_at_request;
  int ticks = 0;
  while (!s.shutdownComplete()) {
    s.apply(Vector3d(1.0, 0.0, 0.0));
    EXPECT_LE(s.gain(), last);
    last = s.gain();
    ASSERT_LT(++ticks, 1000);
  }
  EXPECT_LE(ticks, 200);
}

TEST(Safety, StagesCombine) {
  // The ramp feeds the peak clamp: gain x 100 N is clamped once it reaches the peak.
  SafetyConfig ramped = SafetyConfig::fromSpec(desktop(), kT);
  ramped.continuous_force_n = ramped.peak_force_n;
  SafetyStage r(ramped);
  for (int i = 0; i < 3; ++i) r.apply(Vector3d::Zero());
  const Vector3d huge(100.0, 0.0, 0.0);
  for (int j = 1; j <= 500; ++j) {
    const Vector3d out = r.apply(huge);
    ASSERT_NEAR(out.x(), std::min(7.9, smoothstep(j / 500.0) * 100.0), 1e-9) << j;
    ASSERT_EQ(bool(r.flags() & srv::kSafetyPeakClamped), smoothstep(j / 500.0) * 100.0 > 7.9);
  }

  // At the peak from cold, the budget lasts -tau ln(1 - 1.185^2 / 7.9^2) = 0.114 s; then the drop
  // to the continuous force, 6.7 N, takes two 5 N rate-limited ticks.
  SafetyConfig c = SafetyConfig::fromSpec(desktop(), kT);
  c.ramp_in_s = 0.0;
  SafetyStage s(c);
  for (int i = 0; i < 3; ++i) s.apply(Vector3d::Zero());
  int ticks = 0;
  s.apply(huge);  // 0 -> 5 N, rate limited
  while (!s.continuousLimitActive()) {
    ASSERT_NEAR(s.apply(huge).x(), 7.9, 1e-12);
    ASSERT_LT(++ticks, 200);
  }
  EXPECT_NEAR((ticks + 1) * kT, -5.0 * std::log(1.0 - 1.185 * 1.185 / (7.9 * 7.9)), 2 * kT);
  EXPECT_NEAR(s.apply(huge).x(), 2.9, 1e-12);
  EXPECT_TRUE(s.flags() & srv::kSafetyContinuousLimited);
  EXPECT_TRUE(s.flags() & srv::kSafetyRateLimited);
  EXPECT_NEAR(s.apply(huge).x(), 1.185, 1e-12);

  // NaN during the ramp-out completes the shutdown at once.
  s.requestShutdown();
  s.apply(huge);
  EXPECT_EQ(s.apply(Vector3d(kNaN, 0.0, 0.0)), Vector3d::Zero());
  EXPECT_TRUE(s.shutdownComplete());
  EXPECT_EQ(s.apply(Vector3d(0.0, 0.0, 0.0)), Vector3d::Zero());
  EXPECT_TRUE(s.shutdownComplete());

  // reset() starts over: disengaged, cold.
  s.reset();
  EXPECT_EQ(s.state(), SafetyState::Disengaged);
  EXPECT_EQ(s.meanSquareForceN2(), 0.0);
}

TEST(Safety, FuzzOutputIsFiniteWithinPeakAndRateLimited) {
  SafetyConfig c = SafetyConfig::fromSpec(desktop(), kT);
  c.ramp_in_s = 0.02;
  SafetyStage s(c);
  std::mt19937_64 rng(20240611);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::normal_distribution<double> normal(0.0, 6.0);
  const double specials[] = {kNaN, kInf, -kInf, 1e308, -1e308, 1e-310, 0.0, 7.9, -7.9};
  const double max_step = c.max_force_rate_n_per_s * kT;
  Vector3d prev = Vector3d::Zero();
  int engaged_ticks = 0;
  double mode = 0.0;
  for (int k = 0; k < 20000; ++k) {
    // Blocks of 40 ticks: small requests (so the stage re-engages), ordinary, huge, or specials.
    if (k % 40 == 0) mode = unit(rng);
    Vector3d request;
    for (int i = 0; i < 3; ++i) {
      if (mode < 0.2) {
        request[i] = 0.05 * unit(rng);
      } else if (mode < 0.7) {
        request[i] = normal(rng);
      } else if (mode < 0.85) {
        request[i] = normal(rng) * 1e300;
      } else {
        request[i] = unit(rng) < 0.5 ? normal(rng)
                                     : specials[static_cast<std::size_t>(unit(rng) * 9.0) % 9];
      }
    }
    if (unit(rng) < 0.002) s.disengage();
    const Vector3d out = s.apply(request);
    ASSERT_TRUE(out.allFinite()) << k;
    ASSERT_LE(out.norm(), c.peak_force_n * (1.0 + 1e-12)) << k;
    ASSERT_GE(s.gain(), 0.0);
    ASSERT_LE(s.gain(), 1.0);
    if (s.flags() & (srv::kSafetyDisengaged | srv::kSafetyNonFinite)) {
      ASSERT_EQ(out, Vector3d::Zero()) << k;
    } else {
      // Stepping to zero is the safety stop's privilege; everything else is rate limited.
      ASSERT_LE((out - prev).norm(), max_step * (1.0 + 1e-12)) << k;
      ++engaged_ticks;
    }
    prev = out;
  }
  EXPECT_GT(engaged_ticks, 5000);  // the fuzz spent real time engaged, not only disengaged
  EXPECT_GT(s.counters().peak_clamped, 100u);
  EXPECT_GT(s.counters().rate_limited, 100u);
  EXPECT_GT(s.counters().non_finite, 100u);
}

TEST(Safety, ApplyDoesNotAllocate) {
  SafetyStage s(SafetyConfig::fromSpec(desktop(), kT));
  const long before = thx::test::g_allocations.load();
  for (int k = 0; k < 3000; ++k) {
    s.apply(Vector3d(k < 10 ? 0.0 : 9.0, 1.0, k % 97 == 0 ? kNaN : 0.0));
    if (k == 2000) s.requestShutdown();
    if (k == 1500) s.disengage();
  }
  EXPECT_EQ(thx::test::g_allocations.load(), before);
  void* volatile probe = ::operator new(16);  // the counter does count
  ::operator delete(probe);
  EXPECT_EQ(thx::test::g_allocations.load(), before + 1);
}

}  // namespace test_safety
