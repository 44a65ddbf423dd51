// Two pens pinch and lift a block by friction (issue 30, scenes/two_pens_pinch.yaml), closed loop
// and lock-step in one process: each scene device is hapticd's (its simulated PHANToM and hand
// script, its servo rig as hapticd wires it), physics-client's scene steps on the devices' tips,
// and each pen's force goes back into its device's servo as a client force one tick later, as
// it would over LCM. With grasping pens (a virtual coupling) the block rises with the hands and
// is set down again; with the default kinematic pens the same hands do not lift it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "clients/physics_client/driver.hpp"
#include "clients/physics_client/physics_scene.hpp"
#include "device/sim_phantom.hpp"
#include "scenes/scene_loader.hpp"
#include "server/hapticd_devices.hpp"
#include "server/prepared_scene.hpp"
#include "server/servo_rig.hpp"

namespace test_pinch {

namespace {

using namespace thx;
const std::string kScene = std::string(THX_SOURCE_DIR) + "/scenes/two_pens_pinch.yaml";

Eigen::Vector3d v3(const double (&a)[3]) { return {a[0], a[1], a[2]}; }

struct Outcome {
  double start_z = 0.0;
  double highest_z = 0.0;   // the block's centre, highest over the run
  double held_z = 0.0;      // at the end of the hold at the top (both scripts at 3.2 s)
  double end_z = 0.0;       // after the release
  double end_tilt_deg = 0.0;
  double largest_client_n = 0.0;  // client force, either device, any tick
  double largest_out_n = 0.0;     // what a device was told
  double summary_rise_m = 0.0;    // physics-client's run summary: the block's max_rise_m
  std::uint64_t faults = 0;
  std::uint64_t passivity_ticks = 0;  // both devices' controllers, ticks active
  double passivity_j = 0.0;           // and the energy they took out
};

Outcome runPinch(const physclient::PenOptions& pen) {
  const scene::Scene sc = scene::loadScene(kScene);
  srv::HapticdOptions options;
  options.lockstep = true;
  srv::HapticdDevices devices = srv::makeHapticdDevices(options, sc, nullptr);
  EXPECT_EQ(devices.size(), 2u);
  const auto prepared = srv::prepareScene(sc, kScene, devices.specs, srv::ScenePolicy{});
  std::vector<std::unique_ptr<srv::ServoRig>> rigs;
  for (std::size_t i = 0; i < devices.size(); ++i) {
    rigs.push_back(std::make_unique<srv::ServoRig>(*devices.devices[i].device, prepared->surface.surface,
                                                   prepared->devices[i].wiring));
    devices.devices[i].device->open();
  }
  physclient::SimOptions so;
  so.pen = pen;
  so.pens = int(devices.size());
  physclient::PhysicsScene sim(sc, so);
  physclient::EventSink no_events;
  physclient::Driver driver(sim, no_events, physclient::DriverOptions{double(sc.rates.physics_hz), 60.0, 1000.0});
  std::vector<physclient::Driver::PenInput> tips(devices.size());

  double script_s = 0.0;
  for (const auto& d : devices.devices) script_s = std::max(script_s, d.sim->script().duration());
  const double dt = 1.0 / sc.rates.servo_hz;
  const auto ticks = std::int64_t((script_s + 0.5) / dt);
  const auto held_tick = std::int64_t(3.2 / dt);
  Outcome o;
  o.start_z = sim.body(0).p_world.z();
  o.highest_z = o.start_z;
  for (std::int64_t k = 0; k < ticks; ++k) {
    for (std::size_t i = 0; i < rigs.size(); ++i) {
      const srv::TickRecord& r = rigs[i]->tickAndDrain();
      tips[i].tip_world = v3(r.p_world);
      o.largest_client_n = std::max(o.largest_client_n, v3(r.f_client).norm());
      o.largest_out_n = std::max(o.largest_out_n, v3(r.f_out).norm());
    }
    driver.step(tips);
    for (std::size_t i = 0; i < rigs.size(); ++i) {
      srv::ClientForce f;
      const Eigen::Vector3d sent = sim.penForce(int(i)).sent_world;
      for (int a = 0; a < 3; ++a) f.force_world_n[a] = sent[a];
      rigs[i]->servo().clientForceSlot().write(f);
    }
    const double z = sim.body(0).p_world.z();
    o.highest_z = std::max(o.highest_z, z);
    if (k == held_tick) o.held_z = z;
  }
  const physclient::BodyState block = sim.body(0);
  o.end_z = block.p_world.z();
  const Eigen::Vector3d up = block.q_world * Eigen::Vector3d::UnitZ();
  o.end_tilt_deg = std::acos(std::clamp(std::abs(up.z()), 0.0, 1.0)) * 180.0 / M_PI;
  o.summary_rise_m = driver.summary().objects.at(0).max_rise_m;
  for (std::size_t i = 0; i < rigs.size(); ++i) {
    o.faults += rigs[i]->servo().counters().faults;
    o.passivity_ticks += rigs[i]->passivity().activeTicks();
    o.passivity_j += rigs[i]->passivity().dissipatedEnergy();
    devices.devices[i].device->close();
  }
  return o;
}

void print(const char* what, const Outcome& o) {
  std::printf("[measured] %s: block centre %.1f mm at start, highest %.1f mm, %.1f mm at 3.2 s (held), %.1f mm at the "
              "end (tilt %.1f deg); largest client force %.2f N, largest device force %.2f N, %llu faults; passivity "
              "controllers active %llu ticks, took out %.4f J\n",
              what, o.start_z * 1e3, o.highest_z * 1e3, o.held_z * 1e3, o.end_z * 1e3, o.end_tilt_deg, o.largest_client_n,
              o.largest_out_n, (unsigned long long)o.faults, (unsigned long long)o.passivity_ticks, o.passivity_j);
}

}  // namespace

TEST(Pinch, TwoGraspingPensLiftTheBlockAndSetItDown) {
  physclient::PenOptions pen;
  pen.coupling_n_per_m = 300.0;
  const Outcome o = runPinch(pen);
  print("grasping pens (coupling 300 N/m)", o);
  // The hands rise 30 mm; the block goes with them, less what slips and the hands' sag.
  EXPECT_GT(o.held_z - o.start_z, 0.025);
  EXPECT_LT(o.highest_z - o.start_z, 0.035);
  EXPECT_NEAR(o.summary_rise_m, o.highest_z - o.start_z, 1e-4);  // the summary says how high (h above the plane)
  // Set down where it started, upright (it rests on the bricks again).
  EXPECT_NEAR(o.end_z, o.start_z, 0.002);
  EXPECT_LT(o.end_tilt_deg, 3.0);
  // The squeeze is what the hands push (1.5 N), under the client clamp; the devices stay safe.
  EXPECT_GT(o.largest_client_n, 1.0);
  EXPECT_LE(o.largest_client_n, pen.max_force_n + 1e-9);
  EXPECT_EQ(o.faults, 0u);
}

TEST(Pinch, KinematicPensDoNotLiftIt) {
  // The default pen follows the tip exactly: the squeeze is a penetration answered by impulses the
  // clamp cuts to 2 N, and the block does not rise with the hands.
  const Outcome o = runPinch(physclient::PenOptions{});
  print("kinematic pens", o);
  EXPECT_LT(o.held_z - o.start_z, 0.01);
}

}  // namespace test_pinch
