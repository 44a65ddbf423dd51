// docs/design.md §4 rule 1: nothing in the servo tick allocates. Every operator new in this binary
// is counted (tests/support/allocation_counter.hpp); a full tick pipeline (render with crease
// handling, passivity, safety, flight recorder, ring) runs 5000 ticks of presses and strokes
// across V-valleys, with client forces, a fault and a client's fault reset.
#include <gtest/gtest.h>

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

}  // namespace test_servo_no_alloc
