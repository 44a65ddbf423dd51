// The missed-tick policy on its own (server/missed_tick_policy.hpp): tick sequences from the
// pacer on a virtual clock (stalls are clock advances, so the missed counts are the pacer's own),
// the decisions asserted exactly. No real time anywhere.
#include <gtest/gtest.h>

#include <vector>

#include "base/error.hpp"
#include "device/device_specs.hpp"
#include "rt/pacer.hpp"
#include "server/missed_tick_policy.hpp"

namespace test_missed_tick_policy {

using namespace thx;
using srv::MissedTickAction;
using srv::MissedTickDecision;
using srv::MissedTickMode;
using srv::MissedTickPolicy;
using srv::MissedTickPolicyConfig;
using srv::StallReason;

namespace {

constexpr std::int64_t kPeriodNs = 1'000'000;

// A servo loop on a virtual clock: each step() is one serviced tick; stall(ms) keeps the servo
// away that long before its next wait, as a preempted thread would be.
struct VirtualLoop {
  explicit VirtualLoop(const MissedTickPolicyConfig& c) : policy(c), pacer(clock, kPeriodNs) { pacer.start(); }

  MissedTickDecision step(const Eigen::Vector3d& p = Eigen::Vector3d::Zero(), bool valid = true) {
    const rt::TickTiming t = pacer.wait();
    last_missed = t.missed;
    clock.advance(200'000);  // compute time, well inside the period
    return policy.observe(t.missed, p, valid);
  }
  // Away `periods` periods and a little: the pacer reports exactly `periods` missed, for
  // periods >= 2 (a tick less than a period late runs late; one a period late or more skips every
  // grid point already past, so the pacer never reports a single missed period).
  MissedTickDecision stallThenStep(int periods, const Eigen::Vector3d& p = Eigen::Vector3d::Zero()) {
    clock.advance(std::int64_t(periods) * kPeriodNs + 300'000);
    return step(p);
  }
  std::vector<MissedTickDecision> run(int ticks) {
    std::vector<MissedTickDecision> d;
    for (int k = 0; k < ticks; ++k) d.push_back(step());
    return d;
  }

  MissedTickPolicy policy;
  rt::VirtualClock clock;
  rt::Pacer pacer;
  std::int64_t last_missed = 0;
};

MissedTickPolicyConfig defaults() { return MissedTickPolicyConfig{}; }

bool allRun(const std::vector<MissedTickDecision>& d) {
  for (const MissedTickDecision& x : d) {
    if (x.action != MissedTickAction::Run || x.fault) return false;
  }
  return true;
}

}  // namespace

TEST(MissedTickPolicy, OnTimeTicksRun) {
  VirtualLoop loop(defaults());
  EXPECT_TRUE(allRun(loop.run(1000)));
  EXPECT_DOUBLE_EQ(loop.policy.successRate(), 1.0);
  EXPECT_EQ(loop.policy.counters().ride_throughs, 0u);
}

TEST(MissedTickPolicy, IsolatedStallsAreRiddenThroughWithTheDevicesHeldForce) {
  VirtualLoop loop(defaults());
  loop.run(200);
  // Two periods missed: the device held 0.5 then 0.25 of the force, and still did when we returned.
  MissedTickDecision d = loop.stallThenStep(2);
  ASSERT_EQ(loop.last_missed, 2);
  EXPECT_EQ(d.action, MissedTickAction::RideThrough);
  EXPECT_FALSE(d.fault);
  EXPECT_DOUBLE_EQ(d.held_gain, 0.25);
  EXPECT_DOUBLE_EQ(d.held_periods, 0.75);
  EXPECT_TRUE(allRun(loop.run(200)));
  // Five: the watchdog had dropped the force to zero; the force comes back from zero.
  d = loop.stallThenStep(5);
  ASSERT_EQ(loop.last_missed, 5);
  EXPECT_EQ(d.action, MissedTickAction::RideThrough);
  EXPECT_DOUBLE_EQ(d.held_gain, 0.0);
  EXPECT_DOUBLE_EQ(d.held_periods, 0.75);
  EXPECT_TRUE(allRun(loop.run(200)));
  // The longest gap ridden through: 20 periods.
  d = loop.stallThenStep(20);
  EXPECT_EQ(d.action, MissedTickAction::RideThrough);
  EXPECT_EQ(loop.policy.counters().ride_throughs, 3u);
  EXPECT_EQ(loop.policy.counters().disengaged_ticks, 0u);
}

TEST(MissedTickPolicy, OneMissedPeriodLeftHalfTheForce) {
  // A device whose own timing reports single missed periods (the pacer above never does).
  MissedTickPolicy policy(defaults());
  policy.observe(0, Eigen::Vector3d::Zero(), true);
  const MissedTickDecision d = policy.observe(1, Eigen::Vector3d::Zero(), true);
  EXPECT_EQ(d.action, MissedTickAction::RideThrough);
  EXPECT_DOUBLE_EQ(d.held_gain, 0.5);
  EXPECT_DOUBLE_EQ(d.held_periods, 0.5);
}

TEST(MissedTickPolicy, AStallLongerThanTheLimitDisengagesOnceThenHoldsOffUntilTheWindowRecovers) {
  VirtualLoop loop(defaults());
  loop.run(200);
  const MissedTickDecision d = loop.stallThenStep(21);
  EXPECT_EQ(d.action, MissedTickAction::Disengage);
  EXPECT_EQ(d.reason, StallReason::LongStall);
  EXPECT_TRUE(d.fault);
  EXPECT_DOUBLE_EQ(d.held_gain, 0.0);
  // 21 of the last 100 periods missed: the success rate (0.79) keeps the force off, no new fault,
  // until the gap has left the window: 100 - 22 ticks later (the window holds the 21 missed
  // periods and the faulting tick; at 79 ticks after it only 20 missed periods remain).
  std::vector<MissedTickDecision> after = loop.run(100);
  int held_off = 0;
  for (const MissedTickDecision& x : after) {
    EXPECT_FALSE(x.fault);
    if (x.action == MissedTickAction::Disengage) {
      EXPECT_EQ(x.reason, StallReason::SuccessRate);
      ++held_off;
    }
  }
  EXPECT_EQ(held_off, 78);
  EXPECT_EQ(after[78].action, MissedTickAction::Run);
  EXPECT_EQ(loop.policy.counters().long_stalls, 1u);
  EXPECT_EQ(loop.policy.counters().success_rate, 0u) << "one overload, one fault";
}

TEST(MissedTickPolicy, ABurstOfShortStallsBelowTheSuccessRateDisengages) {
  VirtualLoop loop(defaults());
  loop.run(200);
  // 3 missed every 10 ticks: each stall alone is tolerated; 8 of them put 24 of 100 periods out.
  std::vector<MissedTickDecision> burst;
  for (int s = 0; s < 8; ++s) {
    burst.push_back(loop.stallThenStep(3));
    for (const MissedTickDecision& x : loop.run(6)) burst.push_back(x);
  }
  int first_disengage = -1, faults = 0;
  for (std::size_t k = 0; k < burst.size(); ++k) {
    if (burst[k].fault) ++faults;
    if (first_disengage < 0 && burst[k].action == MissedTickAction::Disengage) first_disengage = int(k);
  }
  // The 7th stall (index 6 x 7 = 42) takes the window to 21 missed periods.
  ASSERT_EQ(first_disengage, 42);
  EXPECT_EQ(burst[std::size_t(first_disengage)].reason, StallReason::SuccessRate);
  EXPECT_EQ(faults, 1);
  for (int k = 0; k < first_disengage; ++k) EXPECT_NE(burst[std::size_t(k)].action, MissedTickAction::Disengage) << k;
  EXPECT_EQ(loop.policy.counters().ride_throughs, 6u);
}

TEST(MissedTickPolicy, SpreadOutStallsNeverTouchTheSuccessRate) {
  VirtualLoop loop(defaults());
  // A 3-tick stall every 50 ticks for 10 s: 6 % of periods missed, never more than 20 of 100.
  int rides = 0;
  for (int s = 0; s < 200; ++s) {
    const MissedTickDecision d = loop.stallThenStep(3);
    EXPECT_EQ(d.action, MissedTickAction::RideThrough) << s;
    rides += d.action == MissedTickAction::RideThrough;
    EXPECT_TRUE(allRun(loop.run(46)));
  }
  EXPECT_EQ(rides, 200);
  EXPECT_EQ(loop.policy.counters().disengaged_ticks, 0u);
}

TEST(MissedTickPolicy, APenThatMovedFarDuringAStallDisengages) {
  MissedTickPolicyConfig c = defaults();
  c.max_jump_m = 0.002;
  VirtualLoop loop(c);
  const Eigen::Vector3d p0(0.01, 0.0, -0.001);
  for (int k = 0; k < 100; ++k) loop.step(p0);
  // 1.9 mm over a 4-tick stall: ridden through.
  MissedTickDecision d = loop.stallThenStep(4, p0 + Eigen::Vector3d(0.0019, 0.0, 0.0));
  EXPECT_EQ(d.action, MissedTickAction::RideThrough);
  // From there 2.1 mm over a 2-tick stall: the proxy's history is not trusted any more.
  d = loop.stallThenStep(2, p0 + Eigen::Vector3d(0.0019, 0.0, -0.0021));
  EXPECT_EQ(d.action, MissedTickAction::Disengage);
  EXPECT_EQ(d.reason, StallReason::Jump);
  EXPECT_TRUE(d.fault);
  EXPECT_EQ(loop.policy.counters().jumps, 1u);
}

TEST(MissedTickPolicy, FastMotionWithoutAGapIsNotTheTimingPolicysBusiness) {
  VirtualLoop loop(defaults());
  loop.step(Eigen::Vector3d::Zero());
  const MissedTickDecision d = loop.step(Eigen::Vector3d(0.01, 0.0, 0.0));
  EXPECT_EQ(d.action, MissedTickAction::Run);
}

TEST(MissedTickPolicy, InvalidReadingsDoNotMoveTheReferencePosition) {
  VirtualLoop loop(defaults());
  const Eigen::Vector3d p0(0.0, 0.0, 0.0);
  loop.step(p0);
  // An invalid reading far away (a device that lost track) is not where the pen was.
  loop.step(Eigen::Vector3d(0.5, 0.0, 0.0), /*valid=*/false);
  const MissedTickDecision d = loop.stallThenStep(2, p0 + Eigen::Vector3d(0.0005, 0.0, 0.0));
  EXPECT_EQ(d.action, MissedTickAction::RideThrough);
}

TEST(MissedTickPolicy, TheOldRuleDisengagesOnEveryGapOfThreeOrMore) {
  MissedTickPolicyConfig c = defaults();
  c.mode = MissedTickMode::DisengageOnGap;
  VirtualLoop loop(c);
  loop.run(100);
  MissedTickDecision d = loop.stallThenStep(2);
  EXPECT_EQ(d.action, MissedTickAction::Run) << "the old rule let short gaps pass untouched";
  EXPECT_DOUBLE_EQ(d.held_gain, 1.0);
  d = loop.stallThenStep(3);
  EXPECT_EQ(d.action, MissedTickAction::Disengage);
  EXPECT_TRUE(d.fault);
  d = loop.stallThenStep(3);  // the very next tick, again: a fault of its own
  EXPECT_TRUE(d.fault);
  EXPECT_TRUE(allRun(loop.run(50)));
  EXPECT_EQ(loop.policy.counters().long_stalls, 2u);
}

TEST(MissedTickPolicy, HapticdsJumpBoundIsTheContinuousForceOverTheStiffness) {
  const dev::DeviceSpec desktop = dev::phantomDesktopSpec();
  const MissedTickPolicyConfig c = MissedTickPolicyConfig::fromSpec(desktop, 600.0, MissedTickMode::RideThrough);
  EXPECT_DOUBLE_EQ(c.max_jump_m, desktop.continuous_force_n / 600.0);
  EXPECT_NEAR(c.max_jump_m, 0.00198, 1e-5);
}

// Issue 30: hapticd's stall bound and success-rate window are times, so the same hiccups of the
// scheduler (two 3 ms stalls 10 ms apart, then a 10 ms one) are ridden through at 1 kHz and at
// 4 kHz alike. Counted in ticks (20 and 100 at every rate), at 4 kHz the two short stalls were 24
// of the last 100 periods (a success-rate fault) and the long one 40 periods (a long stall).
TEST(MissedTickPolicy, TheSameStallsInTimeAreDecidedAlikeAtEveryServoRate) {
  const dev::DeviceSpec desktop = dev::phantomDesktopSpec();
  for (double hz : {1000.0, 4000.0}) {
    const double period = 1.0 / hz;
    const MissedTickPolicyConfig c = MissedTickPolicyConfig::fromSpec(desktop, 600.0, MissedTickMode::RideThrough, period);
    EXPECT_EQ(c.max_stall_ticks, int(std::lround(0.020 * hz)));
    EXPECT_EQ(c.window_ticks, int(std::lround(0.100 * hz)));
    MissedTickPolicy policy(c);
    auto ticks = [&](double seconds) { return std::int64_t(std::lround(seconds * hz)); };
    auto serve = [&](double seconds) {
      for (std::int64_t k = 0; k < ticks(seconds); ++k) EXPECT_EQ(policy.observe(0, Eigen::Vector3d::Zero(), true).action, MissedTickAction::Run);
    };
    serve(0.2);
    EXPECT_EQ(policy.observe(ticks(0.003), Eigen::Vector3d::Zero(), true).action, MissedTickAction::RideThrough) << hz;
    serve(0.010);
    EXPECT_EQ(policy.observe(ticks(0.003), Eigen::Vector3d::Zero(), true).action, MissedTickAction::RideThrough) << hz;
    serve(0.2);
    EXPECT_EQ(policy.observe(ticks(0.010), Eigen::Vector3d::Zero(), true).action, MissedTickAction::RideThrough) << hz;
    serve(0.2);
    EXPECT_EQ(policy.counters().ride_throughs, 3u) << hz;
    EXPECT_EQ(policy.counters().success_rate + policy.counters().long_stalls, 0u) << hz;
  }
  // The 1 kHz defaults are the numbers the policy had before (docs/hapticd.md).
  const MissedTickPolicyConfig at1k = MissedTickPolicyConfig::fromSpec(desktop, 600.0, MissedTickMode::RideThrough);
  EXPECT_EQ(at1k.max_stall_ticks, MissedTickPolicyConfig{}.max_stall_ticks);
  EXPECT_EQ(at1k.window_ticks, MissedTickPolicyConfig{}.window_ticks);
}

TEST(MissedTickPolicy, ABadConfigurationIsRefusedNamingTheField) {
  MissedTickPolicyConfig c = defaults();
  c.window_ticks = 0;
  try {
    MissedTickPolicy p(c);
    FAIL() << "accepted window_ticks = 0";
  } catch (const thx::Error& e) {
    EXPECT_NE(std::string(e.what()).find("window_ticks"), std::string::npos) << e.what();
  }
  c = defaults();
  c.min_success_rate = 1.5;
  EXPECT_THROW(MissedTickPolicy{c}, thx::Error);
}

}  // namespace test_missed_tick_policy
