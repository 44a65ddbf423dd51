// The servo tick's policies, driven lock-step by a scripted device: missed ticks, invalid
// readings, client forces, the safety stage as the last word, shutdown, flight records.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>

#include "tests/server/servo_fixture.hpp"

namespace test_servo {

using namespace thx;
using test::ServoRig;

namespace {
// A press 1 mm below a valley floor, reached from above over 200 ticks.
void press(std::int64_t tick, dev::DeviceState& s) {
  const double z = tick < 200 ? 0.002 - (0.002 + test::kRigValleyDepth + 0.001) * double(tick) / 200.0
                              : -test::kRigValleyDepth - 0.001;
  s.p_world = Eigen::Vector3d(test::kRigFloorX, 0.0, z);
}
}  // namespace

TEST(Servo, PressIntoAValleyEngagesAndRendersUpward) {
  ServoRig rig(press);
  rig.run(1500);  // engage after small force, 0.5 s ramp, then hold
  const Eigen::Vector3d f = rig.device.writes().back();
  EXPECT_NEAR(f.z(), 1000.0 * 0.001, 0.05);  // 1 mm below the floor, both walls held
  EXPECT_LT(std::fabs(f.x()), 0.05);
  EXPECT_EQ(rig.servo().counters().faults, 0u);
  EXPECT_GT(rig.servo().counters().contact_ticks, 1000u);
}

// The servo writes the force before it asks the renderer where the contact is
// (ProxyRenderer::describeContact, after the write): its record still says of every tick what
// render() says, on a stroke that presses into the valleys and slides across their walls.
TEST(Servo, TheRecordSaysWhereTheContactIsAsRenderDoes) {
  ServoRig rig([](std::int64_t tick, dev::DeviceState& s) {
    press(std::min<std::int64_t>(tick, 300), s);
    if (tick > 300) s.p_world.x() += 2e-5 * double(tick - 300);  // 20 mm/s across the valleys
    s.v_world = Eigen::Vector3d(tick > 300 ? 0.02 : 0.0, 0.001, 0.0);
  });
  srv::ProxyRenderer alone(*rig.texture.surface, rig.config().renderer);
  const auto vec = [](const double (&a)[3]) { return Eigen::Vector3d(a[0], a[1], a[2]); };
  int contact = 0;
  for (int k = 0; k < 700; ++k) {
    const srv::TickRecord& r = rig.tickAndDrain();
    const srv::RenderOutput o = alone.render(vec(r.p_world), vec(r.v_world));
    ASSERT_EQ(vec(r.f_render), o.force_world) << k;
    EXPECT_EQ(r.texel_i, o.texel.i) << k;
    EXPECT_EQ(r.texel_j, o.texel.j) << k;
    EXPECT_EQ(r.uv[0], o.uv.u) << k;
    EXPECT_EQ(r.uv[1], o.uv.v) << k;
    EXPECT_EQ(vec(r.p_proj_world), o.p_proj_world) << k;
    EXPECT_EQ(vec(r.n_geom_world), o.n_geom_world) << k;
    EXPECT_EQ(vec(r.n_sampled_world), o.n_sampled_world) << k;
    EXPECT_EQ(r.relief_depth_m, o.relief_depth_m) << k;
    EXPECT_EQ(vec(r.v_tangent_world), o.v_tangent_world) << k;
    EXPECT_EQ(vec(r.tangent_world), o.tangent_world) << k;
    EXPECT_EQ(vec(r.bitangent_world), o.bitangent_world) << k;
    EXPECT_EQ(r.triangle, o.triangle) << k;
    contact += r.in_contact ? 1 : 0;
  }
  EXPECT_GT(contact, 400);
}

TEST(Servo, LongGapDisengagesAndFreezesAFlightRecord) {
  ServoRig rig([](std::int64_t tick, dev::DeviceState& s) {
    press(tick, s);
    if (tick == 1500) s.timing.missed = 25;  // the servo was away for 25 ms: longer than ridden through
  });
  rig.run(1500);
  EXPECT_GT(rig.device.writes().back().norm(), 0.5);
  rig.run(1);  // the tick after the gap: 1525, the fault
  EXPECT_EQ(rig.device.writes().back().norm(), 0.0);
  EXPECT_EQ(rig.servo().counters().faults, 1u);
  EXPECT_EQ(rig.servo().counters().missed_ticks, 25u);
  EXPECT_EQ(rig.safety().state(), srv::SafetyState::Disengaged);
  // The flight record holds the last second up to and including the fault.
  const std::string dir = testing::TempDir();
  const std::string path = rig.recorder().dumpPending(dir);
  ASSERT_FALSE(path.empty());
  std::ifstream in(path);
  int lines = 0;
  std::string line, last;
  while (std::getline(in, line)) {
    ++lines;
    last = line;
  }
  EXPECT_EQ(lines, 2 + 1000);  // comment + header + 1000 ticks
  EXPECT_EQ(last.rfind("1525,25,", 0), 0u) << last;  // the faulting tick, 25 missed
  std::filesystem::remove(path);
  EXPECT_TRUE(rig.recorder().dumpPending(dir).empty());
  // While pressing, the force stays zero: re-engaging needs a small requested force first.
  rig.run(100);
  EXPECT_EQ(rig.device.writes().back().norm(), 0.0);
}

// The gaps a loaded machine makes (a few ms) under a steady press: the force stays on.
TEST(Servo, ShortGapsUnderAPressAreRiddenThroughAtFullForce) {
  ServoRig rig([](std::int64_t tick, dev::DeviceState& s) {
    press(tick, s);
    if (tick == 1500) s.timing.missed = 1;
    if (tick == 1600) s.timing.missed = 5;   // longer than the device's watchdog holds the force
    if (tick == 1700) s.timing.missed = 20;  // the longest ridden through
  });
  rig.run(1500);
  const double held = rig.device.writes().back().z();
  ASSERT_GT(held, 0.9);
  const std::uint64_t full_before = rig.servo().counters().full_force_ticks;
  rig.run(300 - 26);  // every tick from 1500 on, through all three gaps, to tick 1800
  EXPECT_EQ(rig.servo().counters().faults, 0u);
  EXPECT_EQ(rig.servo().counters().missed_ticks, 26u);
  EXPECT_EQ(rig.servo().counters().service_missed_ticks, 26u);
  EXPECT_EQ(rig.safety().state(), srv::SafetyState::Engaged);
  EXPECT_EQ(rig.safety().counters().disengage_events, 0u);
  EXPECT_EQ(rig.servo().missedTickPolicy().counters().ride_throughs, 3u);
  // 1 N is inside one rate-limit step: not one serviced tick below full force.
  EXPECT_EQ(rig.servo().counters().full_force_ticks - full_before, std::uint64_t(300 - 26));
  for (std::size_t k = rig.device.writes().size() - 274; k < rig.device.writes().size(); ++k)
    EXPECT_NEAR(rig.device.writes()[k].z(), held, 0.05) << k;
}

TEST(Servo, TheOldPolicyDisengagesOnAFiveTickGap) {
  ServoRig rig(
      [](std::int64_t tick, dev::DeviceState& s) {
        press(tick, s);
        if (tick == 1500) s.timing.missed = 5;
      },
      true, srv::MissedTickMode::DisengageOnGap);
  rig.run(1501);
  EXPECT_EQ(rig.device.writes().back().norm(), 0.0);
  EXPECT_EQ(rig.servo().counters().faults, 1u);
  EXPECT_EQ(rig.safety().state(), srv::SafetyState::Disengaged);
  rig.run(100);  // pressing: no small request, so the force stays off
  EXPECT_EQ(rig.device.writes().back().norm(), 0.0);
}

TEST(Servo, AGapOverWhichThePenJumpedDisengages) {
  ServoRig rig([](std::int64_t tick, dev::DeviceState& s) {
    press(tick, s);
    if (tick == 1500) s.timing.missed = 2;
    if (tick >= 1500) s.p_world.z() -= 0.0015;  // 1.5 mm deeper after the gap: K x 1.5 mm > 1.185 N
  });
  rig.run(1501);
  EXPECT_EQ(rig.device.writes().back().norm(), 0.0);
  EXPECT_EQ(rig.servo().counters().faults, 1u);
  EXPECT_EQ(rig.servo().missedTickPolicy().counters().jumps, 1u);
}

TEST(Servo, InvalidReadingsTurnTheForceOffAfterThePolicyLimit) {
  ServoRig rig([](std::int64_t tick, dev::DeviceState& s) {
    press(tick, s);
    if (tick >= 1500 && tick < 1502) s.valid = false;                                   // two: tolerated
    if (tick >= 1700 && tick < 1703) s.p_world.x() = std::numeric_limits<double>::quiet_NaN();  // three: fault
  });
  rig.run(1502);
  EXPECT_EQ(rig.servo().counters().faults, 0u);
  EXPECT_EQ(rig.servo().counters().invalid_readings, 2u);
  rig.run(210);
  EXPECT_EQ(rig.servo().counters().faults, 1u);
  EXPECT_EQ(rig.device.writes().back().norm(), 0.0);
  for (const Eigen::Vector3d& f : rig.device.writes()) ASSERT_TRUE(f.allFinite());
}

TEST(Servo, ADeviceThatStaysInvalidFaultsOnceAndGetsNoForce) {
  ServoRig rig([](std::int64_t tick, dev::DeviceState& s) {
    press(tick, s);
    if (tick >= 1500) s.valid = false;  // e.g. the VRPN server went away for good
  });
  rig.run(1500);
  srv::ClientForce cf;
  cf.force_world_n[0] = 0.1;
  for (int k = 0; k < 500; ++k) {
    rig.servo().clientForceSlot().write(cf);  // a client keeps pushing
    rig.run(1);
  }
  EXPECT_EQ(rig.servo().counters().faults, 1u);  // one flight record, not one per tick
  EXPECT_EQ(rig.servo().counters().invalid_readings, 500u);
  EXPECT_EQ(rig.servo().counters().client_force_ticks, 0u) << "never applied to a pen we cannot locate";
  for (std::size_t i = rig.device.writes().size() - 490; i < rig.device.writes().size(); ++i)
    ASSERT_EQ(rig.device.writes()[i].norm(), 0.0) << i;
}

TEST(Servo, ClientForcesAreAddedAndExpire) {
  ServoRig rig([](std::int64_t, dev::DeviceState& s) { s.p_world = Eigen::Vector3d(0, 0, 0.01); });  // free space
  rig.run(10);  // engage (zero request)
  srv::ClientForce cf;
  cf.force_world_n[0] = 0.15;  // below the engage threshold, so it passes the ramp quickly
  rig.servo().clientForceSlot().write(cf);
  rig.run(600);  // ramp-in completes; the force has not been refreshed for 600 ticks ...
  EXPECT_EQ(rig.device.writes().back().norm(), 0.0);  // ... so it expired after 50
  rig.servo().clientForceSlot().write(cf);
  rig.run(10);
  EXPECT_NEAR(rig.device.writes().back().x(), 0.15, 1e-9);
  EXPECT_EQ(rig.servo().counters().client_force_ticks, 51u + 10u);  // the fresh tick + 50, then 10
}

TEST(Servo, OutputNeverExceedsThePeakForce) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> xy(-0.04, 0.04), z(-0.05, 0.005);
  ServoRig rig([&](std::int64_t tick, dev::DeviceState& s) {
    s.p_world = tick < 20 ? Eigen::Vector3d(0, 0, 0.01) : Eigen::Vector3d(xy(rng), xy(rng), z(rng));
    s.v_world = Eigen::Vector3d(xy(rng), xy(rng), xy(rng)) * 100.0;
  });
  rig.run(3000);
  for (const Eigen::Vector3d& f : rig.device.writes()) ASSERT_LE(f.norm(), 7.9 + 1e-9);
}

TEST(Servo, ShutdownRampsTheForceToZero) {
  ServoRig rig(press);
  rig.run(1500);
  const double before = rig.device.writes().back().norm();
  EXPECT_GT(before, 0.5);
  rig.servo().requestShutdown();
  int ticks = 0;
  double previous = before;
  while (!rig.servo().finished() && ticks < 1000) {
    rig.run(1);
    ++ticks;
    EXPECT_LE(rig.device.writes().back().norm(), previous + 1e-9);  // monotone ramp-down
    previous = rig.device.writes().back().norm();
  }
  EXPECT_TRUE(rig.servo().finished());
  EXPECT_EQ(rig.device.writes().back().norm(), 0.0);
  EXPECT_NEAR(ticks, 200, 2);  // ramp_out_s = 0.2 s
}

}  // namespace test_servo
