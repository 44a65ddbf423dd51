// Every FLAG_* bit and FAULT_* code of device_state_t is raised where it happens and reaches a
// 60 Hz DEVICE_STATE subscriber (docs/messages.md §5.1). One scripted session, in lock-step: a
// hover (engage, ramp), a deep press (contact, peak clamp, the continuous-force budget running
// out), a one-tick gap, a client force, a NaN client force, invalid readings, a long gap, a
// scene switch.
#include <gtest/gtest.h>

#include <limits>

#include "tests/server/fault_pipeline.hpp"

namespace test_fault_codes {

using namespace thx;
using D = thx_msgs::device_state_t;

namespace {

constexpr std::int32_t bit(std::int32_t code) { return std::int32_t{1} << code; }

// Device ticks of each event (FakeDevice hands the script the tick index, gaps included).
constexpr std::int64_t kPressFrom = 600, kPressTo = 1400;
constexpr std::int64_t kShortGapAt = 1600;   // 1 missed: FLAG_MISSED_TICK, no fault
constexpr std::int64_t kClientForceAt = 1700;
constexpr std::int64_t kNanForceAt = 1900;
constexpr std::int64_t kInvalidFrom = 2000;  // 3 invalid readings: FAULT_DEVICE_IO at 2002
constexpr std::int64_t kLongGapAt = 2200;    // 25 missed, longer than the policy rides through:
                                             // FAULT_MISSED_TICKS on tick 2225
constexpr std::int64_t kSwitchAt = 2300;     // a scene switch: 200 ticks down, 200 up

void session(std::int64_t tick, dev::DeviceState& s) {
  test::hover(tick, s);
  if (tick >= kPressFrom && tick < kPressTo) {
    // Down to 10 mm below the top of the ridges at 0.1 m/s, into a valley floor: about 6.5 N.
    const double z = std::max(0.002 - 1e-4 * double(tick - kPressFrom), -0.010);
    s.p_world = Eigen::Vector3d(test::kRigFloorX, 0.0, z);
  }
  if (tick == kShortGapAt) s.timing.missed = 1;
  if (tick >= kInvalidFrom && tick < kInvalidFrom + 3) s.valid = false;
  if (tick == kLongGapAt) s.timing.missed = 25;
}

struct FaultCodes : ::testing::Test {
  static void SetUpTestSuite() {
    p = new test::FaultPipeline(session, 60.0);
    static srv::SurfaceSwap same_surface;  // a switch to the surface it renders: only the ramps show
    same_surface.surface = &p->rig.renderer().surface();
    same_surface.renderer = p->rig.renderer().config();
    srv::ClientForce none, small, nan;
    small.force_world_n[0] = 0.1;
    nan.force_world_n[1] = std::numeric_limits<double>::quiet_NaN();
    for (int k = 0; k < 2800; ++k) {
      const std::int64_t next = p->ticks.empty() ? 0 : p->ticks.back().tick + 1;
      if (next == kClientForceAt) p->rig.servo().clientForceSlot().write(small);
      if (next == kClientForceAt + 20) p->rig.servo().clientForceSlot().write(none);
      if (next == kNanForceAt) p->rig.servo().clientForceSlot().write(nan);
      if (next == kNanForceAt + 1) p->rig.servo().clientForceSlot().write(none);  // one tick only
      if (next == kSwitchAt) p->rig.servo().surfaceSwap().offer(&same_surface);
      p->step();
    }
  }
  static void TearDownTestSuite() { delete p; }

  // The tick that raised `fault` first, -1 if none did.
  static std::int64_t firstTickWith(std::uint32_t fault) {
    for (const srv::TickRecord& r : p->ticks) {
      if (r.faults & fault) return r.tick;
    }
    return -1;
  }
  // OR of flags_seen / fault_mask over the messages covering ticks [from, to].
  static std::int32_t flagsSeen(std::int64_t from, std::int64_t to) {
    std::int32_t f = 0;
    for (const D& m : p->sink.state_msgs) {
      if (m.tick >= from && m.tick <= to + 17) f |= m.flags_seen;  // 17: the 60 Hz stream's longest interval
    }
    return f;
  }

  static test::FaultPipeline* p;
};
test::FaultPipeline* FaultCodes::p = nullptr;

}  // namespace

TEST_F(FaultCodes, EveryFlagIsRaisedAndReachesA60HzSubscriber) {
  std::int32_t seen = 0;
  for (const D& m : p->sink.state_msgs) seen |= m.flags_seen;
  const std::int32_t flags[] = {D::FLAG_ENGAGED,      D::FLAG_RAMPING,       D::FLAG_SAFETY_CLAMP,
                                D::FLAG_IN_CONTACT,   D::FLAG_MISSED_TICK,   D::FLAG_CLIENT_FORCE,
                                D::FLAG_SIMULATED,    D::FLAG_FAULT,         D::FLAG_SCENE_SWITCHING,
                                D::FLAG_PROXY_HELD};
  for (std::int32_t flag : flags) {
    EXPECT_TRUE(seen & flag) << "flag " << flag;
  }
  // Each where it happens.
  EXPECT_TRUE(flagsSeen(0, 500) & D::FLAG_RAMPING);  // the engage ramp after start
  EXPECT_TRUE(flagsSeen(kPressFrom, kPressTo) & D::FLAG_IN_CONTACT);
  EXPECT_TRUE(flagsSeen(kPressFrom, kPressTo) & D::FLAG_SAFETY_CLAMP);
  EXPECT_FALSE(flagsSeen(kPressTo + 100, kShortGapAt - 1) & D::FLAG_IN_CONTACT);
  EXPECT_TRUE(flagsSeen(kShortGapAt + 1, kShortGapAt + 1) & D::FLAG_MISSED_TICK);
  EXPECT_TRUE(flagsSeen(kClientForceAt, kClientForceAt + 20) & D::FLAG_CLIENT_FORCE);
  EXPECT_FALSE(flagsSeen(kClientForceAt + 60, kNanForceAt - 20) & D::FLAG_CLIENT_FORCE);
  EXPECT_FALSE(flagsSeen(0, kSwitchAt - 20) & D::FLAG_SCENE_SWITCHING);
  EXPECT_TRUE(flagsSeen(kSwitchAt, kSwitchAt + 20) & D::FLAG_SCENE_SWITCHING);
  EXPECT_TRUE(flagsSeen(kSwitchAt + 380, kSwitchAt + 380) & D::FLAG_SCENE_SWITCHING);  // still ramping up
}

TEST_F(FaultCodes, EveryFaultIsRaisedWhereItHappensAndReachesA60HzSubscriber) {
  const std::int64_t budget = firstTickWith(srv::kFaultForceBudget);
  const std::int64_t nan = firstTickWith(srv::kFaultNonFiniteForce);
  const std::int64_t io = firstTickWith(srv::kFaultInvalidReading);
  const std::int64_t missed = firstTickWith(srv::kFaultMissedTicks);
  EXPECT_GT(budget, kPressFrom);  // the deep press heats the motors past the budget
  EXPECT_LT(budget, kPressTo);
  EXPECT_EQ(nan, kNanForceAt);
  EXPECT_EQ(io, kInvalidFrom + 2);
  EXPECT_EQ(missed, kLongGapAt + 25);  // the tick after the gap

  const std::pair<std::int64_t, std::int32_t> raised[] = {{budget, D::FAULT_FORCE_BUDGET},
                                                          {nan, D::FAULT_NONFINITE_FORCE},
                                                          {io, D::FAULT_DEVICE_IO},
                                                          {missed, D::FAULT_MISSED_TICKS}};
  for (auto [tick, code] : raised) {
    const D* m = p->messageFrom(tick);
    ASSERT_NE(m, nullptr) << code;
    EXPECT_TRUE(m->fault_mask & bit(code)) << "code " << code << " at tick " << tick << ", message " << m->tick;
    EXPECT_TRUE(m->flags_seen & D::FLAG_FAULT) << code;
    EXPECT_EQ(m->fault_code, D::FAULT_FORCE_BUDGET) << "the first fault since start stays latched";
  }
  std::int32_t mask = 0;
  for (const D& m : p->sink.state_msgs) mask |= m.fault_mask;
  EXPECT_EQ(mask, bit(D::FAULT_FORCE_BUDGET) | bit(D::FAULT_NONFINITE_FORCE) | bit(D::FAULT_DEVICE_IO) |
                      bit(D::FAULT_MISSED_TICKS));
}

}  // namespace test_fault_codes
