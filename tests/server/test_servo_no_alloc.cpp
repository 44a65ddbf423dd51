// docs/design.md §4 rule 1: nothing in the servo tick allocates. Every operator new in this binary
// is counted (tests/support/allocation_counter.hpp); a full tick pipeline (render with crease
// handling, passivity, safety, flight recorder, ring) runs 5000 ticks of presses and strokes
// across V-valleys, with client forces, a fault and a client's fault reset.
#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "device/sim_phantom.hpp"
#include "rt/clock.hpp"
#include "server/servo_group.hpp"
#include "server/servo_runner.hpp"
#include "tests/server/servo_fixture.hpp"
#include "tests/support/allocation_counter.hpp"

namespace test_servo_no_alloc {

using namespace thx;

TEST(ServoRealtime, NoAllocationInTheTick) {
  test::ServoRig rig([](std::int64_t tick, dev::DeviceState& s) {
    // Hover, press into a valley, stroke across five valleys and back, lift.
    const double t = double(tick % 5000) / 1000.0;
    const double x = t < 2.0 ? 0.0 : 0.02 * std::sin((t - 2.0) * 2.0);
    const double z = t < 1.0 ? 0.002 - 0.0065 * t : (t < 4.5 ? -0.0045 : 0.002);
    s.p_world = Eigen::Vector3d(x, 0.001 * t, z);
    s.v_world = Eigen::Vector3d(0.04 * std::cos((t - 2.0) * 2.0), 0.001, 0.0);
    if (tick == 2500) s.timing.missed = 3;   // a gap ridden through: the policy's path
    if (tick == 3000) s.timing.missed = 25;  // a long stall, a fault: flight recorder freeze on the path too
  });
  // Everything optional on the tick is on: VRPN effects (none commanded) and the snapshot slot.
  srv::ExternalEffectRenderer effects(1e-3);
  rig.servo().attachExternalEffects(&effects);
  rig.servo().publishSnapshots();
  rig.run(10);  // let lazily initialised runtime pieces settle outside the measurement
  srv::ClientForce cf;
  cf.force_world_n[2] = 0.1;
  const long before = test::g_allocations.load();
  for (int k = 0; k < 5000; ++k) {
    if (k % 10 == 0) rig.servo().clientForceSlot().write(cf);
    if (k == 4000) rig.servo().faultResetSlot().write(srv::FaultReset{1});  // a client's reset
    rig.tickAndDrain();
  }
  EXPECT_EQ(test::g_allocations.load() - before, 0);
  EXPECT_GT(rig.servo().counters().contact_ticks, 2000u);
  // Two faults on the path: the 25-tick stall, and the continuous-force budget running out in the
  // long press (the safety stage limits the force from then on).
  EXPECT_EQ(rig.servo().counters().faults, 2u);
  EXPECT_GT(rig.safety().counters().continuous_limited, 0u);
  EXPECT_EQ(rig.servo().missedTickPolicy().counters().ride_throughs, 1u);
}

// The run loop around the tick (server/servo_runner.hpp) adds no allocation either: its steps,
// the lock-step back-pressure check, the stop and the whole ramp-down.
TEST(ServoRealtime, NoAllocationInTheRunLoop) {
  test::ServoRig rig([](std::int64_t tick, dev::DeviceState& s) {
    s.p_world = Eigen::Vector3d(0.0, 0.0, tick < 500 ? 0.002 - 0.00001 * double(tick) : -0.003);
  });
  srv::ServoRunnerOptions o;
  o.lockstep = true;
  o.stop_tick = 3000;
  srv::ServoRunner runner(rig.servo(), rig.ring(), o);
  for (int k = 0; k < 10; ++k) runner.step();  // settle outside the measurement
  rig.drain();
  const long before = test::g_allocations.load();
  int steps = 0;
  for (srv::ServoRunner::Step s = runner.step(); s != srv::ServoRunner::Step::Finished && steps < 100000;
       s = runner.step(), ++steps) {
    rig.drain();
  }
  EXPECT_EQ(test::g_allocations.load() - before, 0);
  EXPECT_TRUE(rig.servo().finished());
  EXPECT_GT(runner.ticks(), 3000);
}

// Several devices under one clock (server/servo_group.hpp): the run loop over the group, the
// group's tick, each simulated PHANToM read at the group's tick (readTick) and the ramp-down add
// no allocation.
TEST(ServoRealtime, NoAllocationInTheGroupTick) {
  test::GeneratedSurface texture(test::ServoRigInputs::vvalley(), /*relief=*/true);
  struct Member {
    Member(const tex::TexturedSurface& surface, double y)
        : device(simConfig(), script(y)), rig(device, surface, test::unitTestWiring(800.0)) {
      device.open();
    }
    static dev::SimPhantomConfig simConfig() {
      dev::SimPhantomConfig c;
      c.lockstep = true;
      return c;
    }
    static dev::HandScript script(double y) {
      dev::HandStroke s;
      s.from_m = {-0.01, y};
      s.to_m = {0.01, y};
      s.speed_m_per_s = 0.04;
      s.force_n = 1.5;
      return dev::HandScript({s});
    }
    dev::SimPhantom device;
    srv::ServoRig rig;
  };
  std::vector<std::unique_ptr<Member>> members;
  rt::VirtualClock clock;
  srv::ServoGroup group(clock, 1'000'000);
  for (int i = 0; i < 3; ++i) {
    members.push_back(std::make_unique<Member>(*texture.surface, -0.02 + 0.02 * i));
    group.add(members.back()->rig.servo());
  }
  group.start();
  srv::ServoRunnerOptions o;
  o.lockstep = true;
  o.stop_tick = 1500;
  srv::ServoRunner runner(group, o);
  const auto stepAndDrain = [&] {
    const srv::ServoRunner::Step s = runner.step();
    for (auto& m : members) m->rig.drain();
    return s;
  };
  for (int k = 0; k < 10; ++k) stepAndDrain();
  const long before = test::g_allocations.load();
  for (int k = 0; k < 10000 && stepAndDrain() != srv::ServoRunner::Step::Finished; ++k) {
  }
  EXPECT_EQ(test::g_allocations.load() - before, 0);
  EXPECT_TRUE(group.finished());
  for (auto& m : members) EXPECT_GT(m->rig.servo().counters().contact_ticks, 500u);
}

}  // namespace test_servo_no_alloc
