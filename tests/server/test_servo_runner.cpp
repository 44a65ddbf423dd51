// The servo run loop (server/servo_runner.hpp), deterministic: the simulated PHANToM on its
// virtual clock (lock-step), the servo wired as hapticd wires it. What is checked is what the loop
// decides (when it ticks, waits, ramps down, stops), never how long anything took.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "device/device_specs.hpp"
#include "device/sim_phantom.hpp"
#include "rt/clock.hpp"
#include "server/servo_group.hpp"
#include "server/servo_runner.hpp"
#include "server/safety.hpp"
#include "server/servo_rig.hpp"
#include "tests/server/servo_fixture.hpp"
#include "tests/support/servo_inputs.hpp"

namespace test_servo_runner {

namespace {

using thx::srv::ServoRunner;
using thx::srv::ServoRunnerOptions;
using thx::srv::TickRecord;
using Step = ServoRunner::Step;

// The simulated PHANToM on a virtual clock (the pen hovers) and a rig with a ring of `ring_records`.
struct LockstepRig {
  explicit LockstepRig(std::size_t ring_records = 16)
      : device(simConfig()),
        texture(thx::test::ServoRigInputs::vvalley(), /*relief=*/true),
        rig(device, *texture.surface, wiring(ring_records)) {
    device.open();
  }
  static thx::dev::SimPhantomConfig simConfig() {
    thx::dev::SimPhantomConfig c;
    c.lockstep = true;
    return c;
  }
  static thx::srv::ServoRigConfig wiring(std::size_t ring_records) {
    thx::srv::ServoRigConfig c = thx::test::unitTestWiring(500.0);
    c.ring_records = ring_records;
    return c;
  }
  // Everything in the ring, oldest first.
  std::vector<TickRecord> drain() {
    std::vector<TickRecord> out;
    TickRecord r;
    while (rig.ring().pop(r)) out.push_back(r);
    return out;
  }

  thx::dev::SimPhantom device;
  thx::test::GeneratedSurface texture;
  thx::srv::ServoRig rig;
};

ServoRunnerOptions lockstep(std::int64_t stop_tick = -1) {
  ServoRunnerOptions o;
  o.lockstep = true;
  o.stop_tick = stop_tick;
  return o;
}

// Steps until Finished; the test fails instead of spinning if the loop never ends.
void stepToEnd(ServoRunner& runner, int max_steps = 100000) {
  for (int k = 0; k < max_steps; ++k) {
    const Step s = runner.step();
    ASSERT_NE(s, Step::WaitingForReader);
    if (s == Step::Finished) return;
  }
  FAIL() << "the servo did not finish";
}

}  // namespace

TEST(ServoRunner, StopTickAfterADuration) {
  EXPECT_EQ(thx::srv::stopTickAfter(2.5, 1000.0), 2500);
  EXPECT_EQ(thx::srv::stopTickAfter(7.5, 500.0), 3750);
  EXPECT_EQ(thx::srv::stopTickAfter(0.0, 1000.0), -1);  // 0: until stopped
}

TEST(ServoRunner, RunsToItsStopTickThenThroughTheRampDownToZeroForce) {
  LockstepRig r(4096);
  ServoRunner runner(r.rig.servo(), r.rig.ring(), lockstep(/*stop_tick=*/100));
  runner.run();
  EXPECT_TRUE(r.rig.servo().finished());
  EXPECT_EQ(runner.step(), Step::Finished);  // and stays finished

  const std::vector<TickRecord> ticks = r.drain();
  ASSERT_EQ(std::int64_t(ticks.size()), runner.ticks());  // every tick's record, none dropped
  EXPECT_EQ(r.rig.ring().dropped(), 0u);
  for (std::size_t k = 0; k < ticks.size(); ++k) {
    EXPECT_EQ(ticks[k].tick, ticks[0].tick + std::int64_t(k));  // no tick skipped on the virtual clock
    const bool ramping = (ticks[k].safety_flags & thx::srv::kSafetyRampingOut) != 0;
    if (ticks[k].tick <= 100) {
      EXPECT_FALSE(ramping) << ticks[k].tick;  // asked on tick 100, acts from 101
    }
  }
  ASSERT_GT(ticks.back().tick, 101);  // the ramp-down took ticks of its own
  EXPECT_TRUE(ticks[ticks.size() - 2].safety_flags & thx::srv::kSafetyRampingOut);
  for (double f : ticks.back().f_out) EXPECT_EQ(f, 0.0);
  // Device time is the virtual clock's: one period per tick.
  EXPECT_NEAR(runner.deviceTimeS(1e-3), double(runner.ticks()) * 1e-3, 1e-9);
}

TEST(ServoRunner, StopAndTheStopFlagRampDownOnce) {
  std::int64_t ramp_ticks = -1;
  for (int way = 0; way < 2; ++way) {
    LockstepRig r(4096);
    std::atomic<bool> flag{false};
    ServoRunnerOptions o = lockstep();
    o.stop_flag = &flag;
    ServoRunner runner(r.rig.servo(), r.rig.ring(), o);
    for (int k = 0; k < 50; ++k) ASSERT_EQ(runner.step(), Step::Ticked);  // no stop tick: runs on
    EXPECT_FALSE(r.rig.servo().finished());
    if (way == 0) {
      runner.stop();
    } else {
      flag.store(true);
    }
    stepToEnd(runner);
    EXPECT_TRUE(r.rig.servo().finished());
    // Both ways ramp down over the same number of ticks (the safety stage's ramp, started once).
    if (ramp_ticks < 0) ramp_ticks = runner.ticks() - 50;
    EXPECT_EQ(runner.ticks() - 50, ramp_ticks);
    EXPECT_GT(ramp_ticks, 1);
    r.drain();
  }
}

TEST(ServoRunner, LockstepBackPressureWaitsForTheReaderInsteadOfDroppingTicks) {
  LockstepRig r(16);
  const std::size_t capacity = r.rig.ring().capacity();
  ServoRunner runner(r.rig.servo(), r.rig.ring(), lockstep());
  // Nobody reads: the loop ticks until the ring holds capacity - 2 records, then waits.
  for (std::size_t k = 0; k + 2 < capacity; ++k) ASSERT_EQ(runner.step(), Step::Ticked) << k;
  EXPECT_EQ(runner.step(), Step::WaitingForReader);
  EXPECT_EQ(runner.step(), Step::WaitingForReader);  // waiting does not tick
  EXPECT_EQ(runner.ticks(), std::int64_t(capacity - 2));
  EXPECT_EQ(r.rig.ring().size(), capacity - 2);
  // The reader takes one: exactly one more tick, then it waits again.
  TickRecord taken;
  ASSERT_TRUE(r.rig.ring().pop(taken));
  EXPECT_EQ(runner.step(), Step::Ticked);
  EXPECT_EQ(runner.step(), Step::WaitingForReader);
  EXPECT_EQ(r.rig.ring().dropped(), 0u);
  // A stop does not skip the back-pressure: the ramp-down waits for the reader too.
  runner.stop();
  EXPECT_EQ(runner.step(), Step::WaitingForReader);
  std::int64_t read = 1;
  for (int k = 0; k < 100000; ++k) {
    const Step s = runner.step();
    if (s == Step::Finished) break;
    if (s == Step::WaitingForReader) read += std::int64_t(r.drain().size());
  }
  read += std::int64_t(r.drain().size());
  EXPECT_TRUE(r.rig.servo().finished());
  EXPECT_EQ(read, runner.ticks());
  EXPECT_EQ(r.rig.ring().dropped(), 0u);
}

TEST(ServoRunner, InRealTimeAFullRingDropsRecordsAndTheServoKeepsTicking) {
  LockstepRig r(16);  // the device's clock is still virtual: only the loop's policy differs
  ServoRunnerOptions o;
  o.lockstep = false;
  ServoRunner runner(r.rig.servo(), r.rig.ring(), o);
  for (int k = 0; k < 40; ++k) ASSERT_EQ(runner.step(), Step::Ticked) << k;
  EXPECT_EQ(runner.ticks(), 40);
  EXPECT_GT(r.rig.ring().dropped(), 0u);
  EXPECT_EQ(std::uint64_t(r.drain().size()) + r.rig.ring().dropped(), 40u);
}

TEST(ServoRunner, OnItsOwnThreadALockstepReaderMissesNoTick) {
  LockstepRig r(16);  // a small ring: the servo waits for the reader again and again
  r.device.close();   // start() opens the device on the servo thread
  ServoRunner runner(r.rig.servo(), r.rig.ring(), lockstep(/*stop_tick=*/500));
  thx::srv::RealtimeOptions rt;
  rt.fifo = false;
  rt.lock_memory = false;
  runner.start(r.device, rt);
  std::vector<std::int64_t> seen;
  while (!runner.done()) {
    TickRecord rec;
    if (r.rig.ring().pop(rec)) seen.push_back(rec.tick);
    else std::this_thread::yield();
  }
  runner.join();
  for (const TickRecord& rec : r.drain()) seen.push_back(rec.tick);
  EXPECT_EQ(runner.error(), "");
  EXPECT_TRUE(r.rig.servo().finished());
  ASSERT_EQ(std::int64_t(seen.size()), runner.ticks());
  EXPECT_GT(runner.ticks(), 500);
  for (std::size_t k = 1; k < seen.size(); ++k) ASSERT_EQ(seen[k], seen[k - 1] + 1) << k;
  EXPECT_EQ(r.rig.ring().dropped(), 0u);
}

namespace {

// A device whose open() fails, as a VRPN server that does not answer would; `shares_clock`: one a
// group would take.
class UnopenableDevice final : public thx::dev::HapticDevice {
 public:
  explicit UnopenableDevice(std::string reason, bool shares_clock = false)
      : reason_(std::move(reason)), shares_clock_(shares_clock) {}
  const thx::dev::DeviceSpec& spec() const override { return spec_; }
  thx::dev::OutputMode outputMode() const override { return thx::dev::OutputMode::Force; }
  void open() override { throw std::runtime_error(reason_); }
  void close() override {}
  thx::dev::DeviceState read() override { return {}; }
  void write(const thx::dev::DeviceCommand&) override {}
  bool sharesClock() const override { return shares_clock_; }

 private:
  thx::dev::DeviceSpec spec_ = thx::dev::phantomDesktopSpec();
  std::string reason_;
  bool shares_clock_;
};

}  // namespace

TEST(ServoRunner, ADeviceThatCannotOpenEndsTheThreadWithItsReasonAndNoTick) {
  LockstepRig r(16);
  UnopenableDevice bad("no answer from Phantom0@nowhere");
  ServoRunner runner(r.rig.servo(), r.rig.ring(), lockstep(10));
  thx::srv::RealtimeOptions rt;
  rt.fifo = false;
  rt.lock_memory = false;
  runner.start(bad, rt);
  runner.join();
  EXPECT_TRUE(runner.done());
  EXPECT_EQ(runner.error(), "cannot open the device: no answer from Phantom0@nowhere");
  EXPECT_EQ(runner.ticks(), 0);
}

// Several devices under one clock (server/servo_group.hpp): the same loop over the group.
namespace {

struct LockstepGroup {
  LockstepGroup() : group(clock, 1'000'000) {
    for (auto& m : members) group.add(m.rig.servo());
  }
  thx::rt::VirtualClock clock;
  LockstepRig members[2]{LockstepRig(16), LockstepRig(16)};  // rings of 16 records
  thx::srv::ServoGroup group;
};

}  // namespace

TEST(ServoRunner, AGroupWaitsForTheReaderOfAnyMembersRing) {
  LockstepGroup g;
  g.group.start();
  ServoRunner runner(g.group, lockstep());
  const std::size_t capacity = g.members[0].rig.ring().capacity();
  for (std::size_t k = 0; k + 2 < capacity; ++k) {
    ASSERT_EQ(runner.step(), Step::Ticked) << k;
    g.members[0].drain();  // member 0's reader keeps up, member 1's does not
  }
  EXPECT_EQ(runner.step(), Step::WaitingForReader);
  g.members[1].drain();
  EXPECT_EQ(runner.step(), Step::Ticked);
  EXPECT_EQ(g.members[0].rig.ring().dropped() + g.members[1].rig.ring().dropped(), 0u);
}

TEST(ServoRunner, OnItsOwnThreadAGroupOpensEveryDeviceAndItsReadersMissNoTick) {
  LockstepGroup g;
  for (auto& m : g.members) m.device.close();  // start() opens them on the servo thread
  ServoRunner runner(g.group, lockstep(/*stop_tick=*/400));
  thx::srv::RealtimeOptions rt;
  rt.fifo = false;
  rt.lock_memory = false;
  runner.start(rt);
  std::vector<std::int64_t> seen[2];
  const auto take = [&] {
    for (int i = 0; i < 2; ++i)
      for (const TickRecord& rec : g.members[i].drain()) seen[i].push_back(rec.tick);
  };
  while (!runner.done()) {
    take();
    std::this_thread::yield();
  }
  runner.join();
  take();
  EXPECT_EQ(runner.error(), "");
  EXPECT_TRUE(g.group.finished());
  EXPECT_GT(runner.ticks(), 400);
  for (int i = 0; i < 2; ++i) {
    ASSERT_EQ(std::int64_t(seen[i].size()), runner.ticks()) << "device " << i;
    for (std::size_t k = 1; k < seen[i].size(); ++k) ASSERT_EQ(seen[i][k], seen[i][k - 1] + 1) << k;
  }
}

namespace {

// The simulated PHANToM, counting the closes start() makes after another device failed.
class CountingSim final : public thx::dev::HapticDevice {
 public:
  const thx::dev::DeviceSpec& spec() const override { return sim.spec(); }
  thx::dev::OutputMode outputMode() const override { return sim.outputMode(); }
  void open() override { sim.open(); ++opens; }
  void close() override { sim.close(); ++closes; }
  thx::dev::DeviceState read() override { return sim.read(); }
  void write(const thx::dev::DeviceCommand& c) override { sim.write(c); }
  bool sharesClock() const override { return true; }
  thx::dev::DeviceState readTick(const thx::rt::TickTiming& t) override { return sim.readTick(t); }
  thx::dev::SimPhantom sim{LockstepRig::simConfig()};
  int opens = 0, closes = 0;
};

}  // namespace

TEST(ServoRunner, AGroupDeviceThatCannotOpenEndsTheThreadNamingItAndClosesTheOthers) {
  thx::test::GeneratedSurface texture(thx::test::ServoRigInputs::vvalley(), /*relief=*/true);
  CountingSim good;
  UnopenableDevice bad("no answer from Phantom1@nowhere", /*shares_clock=*/true);
  thx::srv::ServoRig good_rig(good, *texture.surface, LockstepRig::wiring(16));
  thx::srv::ServoRig bad_rig(bad, *texture.surface, LockstepRig::wiring(16));
  thx::rt::VirtualClock clock;
  thx::srv::ServoGroup group(clock, 1'000'000);
  group.add(good_rig.servo());
  group.add(bad_rig.servo());
  ServoRunner runner(group, lockstep(10));
  thx::srv::RealtimeOptions rt;
  rt.fifo = false;
  rt.lock_memory = false;
  runner.start(rt);
  runner.join();
  EXPECT_EQ(runner.error(), "cannot open device 1: no answer from Phantom1@nowhere");
  EXPECT_EQ(runner.ticks(), 0);
  EXPECT_EQ(good.opens, 1);
  EXPECT_EQ(good.closes, 1);
}

}  // namespace test_servo_runner
