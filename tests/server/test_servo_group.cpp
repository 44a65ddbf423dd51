// Several devices under one servo clock (server/servo_group.hpp), in lock-step: simulated PHANToMs
// stroking a V-valley relief, each behind its own servo. What is checked is what the group
// decides (each device's force, faults, missed periods, shutdown), never how long it took.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "base/error.hpp"
#include "device/sim_phantom.hpp"
#include "rt/clock.hpp"
#include "server/servo_group.hpp"
#include "server/servo_rig.hpp"
#include "tests/server/fake_device.hpp"
#include "tests/server/servo_fixture.hpp"
#include "tests/support/servo_inputs.hpp"

namespace test_servo_group {

namespace {

using thx::srv::ServoGroup;
using thx::srv::TickRecord;

constexpr int kTicks = 1400;  // every stroke's descent, stroke across the valleys and ascent
constexpr int kAllPressing = 500;  // a tick at which every device's pen is in a valley

// Device `i` strokes across the valleys on its own line, at its own speed and push.
thx::dev::HandScript strokeOf(int i) {
  thx::dev::HandStroke s;
  s.from_m = {-0.012 + 0.001 * i, -0.03 + 0.02 * i};
  s.to_m = {0.012, -0.03 + 0.02 * i + 0.002};
  s.speed_m_per_s = 0.03 + 0.01 * i;
  s.force_n = 1.0 + 0.3 * i;
  thx::dev::HandScriptOptions o;
  o.approach_s = 0.1;
  return thx::dev::HandScript({s}, o);
}

thx::dev::SimPhantomConfig simConfig() {
  thx::dev::SimPhantomConfig c;
  c.lockstep = true;
  return c;
}

thx::srv::ServoRigConfig wiring() {
  thx::srv::ServoRigConfig c = thx::test::unitTestWiring(800.0);
  c.quantisation_play = true;  // the simulated encoders quantise, as hapticd's wiring assumes
  return c;
}

// One device and the servo around it.
struct Member {
  Member(const thx::tex::TexturedSurface& surface, int i, thx::dev::SimFaults faults = {})
      : device(withFaults(simConfig(), faults), strokeOf(i)), rig(device, surface, wiring()) {
    device.open();
  }
  static thx::dev::SimPhantomConfig withFaults(thx::dev::SimPhantomConfig c, thx::dev::SimFaults f) {
    c.faults = f;
    return c;
  }
  // The ring emptied into `records`.
  void drainInto(std::vector<TickRecord>& records) {
    TickRecord r;
    while (rig.ring().pop(r)) records.push_back(r);
  }
  thx::dev::SimPhantom device;
  thx::srv::ServoRig rig;
};

double forceDifference(const TickRecord& a, const TickRecord& b) {
  return std::sqrt(std::pow(a.f_out[0] - b.f_out[0], 2) + std::pow(a.f_out[1] - b.f_out[1], 2) +
                   std::pow(a.f_out[2] - b.f_out[2], 2));
}
double forceNorm(const TickRecord& r) {
  return std::sqrt(r.f_out[0] * r.f_out[0] + r.f_out[1] * r.f_out[1] + r.f_out[2] * r.f_out[2]);
}

// Device i alone, on its own pacer (SimPhantom's virtual clock), for n ticks.
std::vector<TickRecord> alone(const thx::tex::TexturedSurface& surface, int i, int n, thx::dev::SimFaults faults = {}) {
  Member m(surface, i, faults);
  std::vector<TickRecord> records;
  for (int k = 0; k < n; ++k) {
    m.rig.tick();
    m.drainInto(records);
  }
  return records;
}

struct ServoGroupTest : ::testing::Test {
  thx::test::GeneratedSurface texture{thx::test::ServoRigInputs::vvalley(), /*relief=*/true};
  const thx::tex::TexturedSurface& surface() const { return *texture.surface; }
};

// `count` members of which `faulty` (if >= 0) gets `faults`, on one virtual clock.
struct Group {
  Group(const thx::tex::TexturedSurface& surface, int count, int faulty = -1, thx::dev::SimFaults faults = {})
      : group(clock, 1'000'000) {
    for (int i = 0; i < count; ++i) members.push_back(std::make_unique<Member>(surface, i, i == faulty ? faults : thx::dev::SimFaults{}));
    records.resize(std::size_t(count));
    for (int i = 0; i < count; ++i) group.add(members[std::size_t(i)]->rig.servo(), "pen");
    group.start();
  }
  void run(int n) {
    for (int k = 0; k < n; ++k) tick();
  }
  void tick() {
    group.tick();
    for (std::size_t i = 0; i < members.size(); ++i) members[i]->drainInto(records[i]);
  }
  thx::rt::VirtualClock clock;
  ServoGroup group;
  std::vector<std::unique_ptr<Member>> members;
  std::vector<std::vector<TickRecord>> records;
};

}  // namespace

TEST_F(ServoGroupTest, EachOfFourDevicesGetsTheForceItGetsAlone) {
  Group g(surface(), 4);
  g.run(kTicks);
  for (int i = 0; i < 4; ++i) {
    SCOPED_TRACE("device " + std::to_string(i));
    const std::vector<TickRecord> solo = alone(surface(), i, kTicks);
    const std::vector<TickRecord>& grouped = g.records[std::size_t(i)];
    ASSERT_EQ(grouped.size(), solo.size());
    double worst = 0.0, peak = 0.0;
    int contact = 0;
    for (std::size_t k = 0; k < solo.size(); ++k) {
      ASSERT_EQ(grouped[k].tick, solo[k].tick);
      worst = std::max(worst, forceDifference(grouped[k], solo[k]));
      peak = std::max(peak, forceNorm(solo[k]));
      contact += solo[k].in_contact ? 1 : 0;
    }
    EXPECT_LE(worst, 1e-12);
    // The strokes press into the valleys: the forces compared are the texture's, not zeros.
    EXPECT_GT(peak, 0.5);
    EXPECT_GT(contact, 400);
  }
  // The devices' strokes differ, so their forces do.
  EXPECT_GT(forceDifference(g.records[0][kAllPressing], g.records[1][kAllPressing]), 0.05);
}

TEST_F(ServoGroupTest, AFaultyDeviceLosesItsForceAndNoOtherDoes) {
  thx::dev::SimFaults lies;  // NaN readings while claiming to be valid, from tick 500 on
  lies.nan_from_tick = kAllPressing;
  lies.nan_ticks = 10;
  Group g(surface(), 3, /*faulty=*/1, lies);
  g.run(kTicks);

  const std::vector<TickRecord>& bad = g.records[1];
  ASSERT_EQ(bad.size(), std::size_t(kTicks));
  EXPECT_GT(forceNorm(bad[kAllPressing - 10]), 0.3);  // pressing before the fault
  EXPECT_EQ(bad[kAllPressing - 10].fault_latched, 0u);
  EXPECT_NE(bad[kAllPressing + 15].fault_latched, 0u);
  EXPECT_EQ(forceNorm(bad[kAllPressing + 15]), 0.0);  // disengaged: no force while it re-engages

  for (int i : {0, 2}) {
    SCOPED_TRACE("device " + std::to_string(i));
    const std::vector<TickRecord> solo = alone(surface(), i, kTicks);
    const std::vector<TickRecord>& grouped = g.records[std::size_t(i)];
    ASSERT_EQ(grouped.size(), solo.size());
    double worst = 0.0;
    for (std::size_t k = 0; k < solo.size(); ++k) {
      worst = std::max(worst, forceDifference(grouped[k], solo[k]));
      EXPECT_EQ(grouped[k].fault_latched, 0u) << "tick " << k;
    }
    EXPECT_LE(worst, 1e-12);
  }
}

TEST_F(ServoGroupTest, AMissedPeriodIsMissedByEveryDeviceAlike) {
  Group g(surface(), 3);
  g.run(300);
  g.clock.advance(4'500'000);  // the group's thread stalled for 4.5 periods
  g.tick();
  for (std::size_t i = 0; i < 3; ++i) {
    const TickRecord& r = g.records[i].back();
    EXPECT_EQ(r.missed, 4) << "device " << i;
    EXPECT_EQ(r.tick, 300 + 4) << "device " << i;
  }
  EXPECT_EQ(g.group.member(0).counters().missed_ticks, 4u);
  EXPECT_EQ(g.group.member(2).counters().missed_ticks, 4u);
}

TEST_F(ServoGroupTest, ShutdownRampsEveryDeviceDown) {
  Group g(surface(), 2);
  g.run(kAllPressing);  // both pressing
  ASSERT_GT(forceNorm(g.records[0].back()) * forceNorm(g.records[1].back()), 0.0);
  g.group.requestShutdown();
  int ticks = 0;
  while (!g.group.finished() && ticks < 2000) {
    g.tick();
    ++ticks;
  }
  EXPECT_TRUE(g.group.finished());
  EXPECT_GT(ticks, 10);  // a ramp, not a cut
  EXPECT_EQ(forceNorm(g.records[0].back()), 0.0);
  EXPECT_EQ(forceNorm(g.records[1].back()), 0.0);
}

TEST_F(ServoGroupTest, RefusesADeviceThatPacesItselfAndMoreThanTheLimit) {
  thx::rt::VirtualClock clock;
  ServoGroup group(clock, 1'000'000);
  thx::test::ServoRig paced_by_itself(thx::test::FakeDevice::Script([](std::int64_t, thx::dev::DeviceState&) {}));
  try {
    group.add(paced_by_itself.servo(), "replay");
    FAIL() << "a device that paces itself was accepted";
  } catch (const thx::Error& e) {
    EXPECT_NE(std::string(e.what()).find("device 0 'replay'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("cannot be read at another clock's tick"), std::string::npos) << e.what();
  }
  EXPECT_EQ(group.size(), 0);

  Member one(surface(), 0);
  group.add(one.rig.servo());
  EXPECT_THROW(group.add(one.rig.servo()), thx::Error);  // the same servo twice
  std::vector<std::unique_ptr<Member>> more;
  for (int i = 1; i < ServoGroup::kMaxDevices; ++i) {
    more.push_back(std::make_unique<Member>(surface(), 0));
    group.add(more.back()->rig.servo());
  }
  EXPECT_EQ(group.size(), ServoGroup::kMaxDevices);
  Member extra(surface(), 0);
  try {
    group.add(extra.rig.servo(), "pen 17");
    FAIL() << "a 17th device was accepted";
  } catch (const thx::Error& e) {
    EXPECT_NE(std::string(e.what()).find("at most 16 devices"), std::string::npos) << e.what();
  }
}

}  // namespace test_servo_group
