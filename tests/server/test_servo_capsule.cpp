// The pen with extent in the servo (issue 30; server/servo.hpp, capsule_tool.hpp): a scene's
// device.tool: capsule renders through the same pipeline as the point pen. The tool's force goes
// through the passivity controller and the safety stage to the device; its torque reaches a
// device that displays torque, following the safety stage's ramps and stopping with the force; a
// force-only device gets the force alone; a scene switch takes the tool and gives it back; the
// default scene's stroke and press hold the capsule out of the bricks.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <numbers>

#include "device/device_specs.hpp"
#include "device/sim_phantom.hpp"
#include "scenes/scene_loader.hpp"
#include "server/prepared_scene.hpp"
#include "server/scene_device.hpp"
#include "tests/server/servo_fixture.hpp"
#include "tests/support/allocation_counter.hpp"
#include "tests/support/error_text.hpp"
#include "tests/support/temp_dir.hpp"

namespace test_servo_capsule {

using namespace thx;

namespace {

Eigen::Vector3d v3(const double (&a)[3]) { return {a[0], a[1], a[2]}; }

// The shaft leans 30 degrees towards +y, along the rig's valleys (they run along y), so only the
// tip's ball meets the walls.
const Eigen::Quaterniond kLean(Eigen::AngleAxisd(-std::numbers::pi / 6, Eigen::Vector3d::UnitX()));

// Ticks 0-999: the tip comes down from 5 mm above z = 0 into the valley at x = 0 to 2 mm below its
// floor; held there (ticks 1000-2999); tick 2000's reading is invalid, which makes the servo's
// renderer (here the tool) start afresh.
void pressIntoTheValley(std::int64_t tick, dev::DeviceState& s) {
  const double top = 0.005, low = -test::kRigValleyDepth - 0.002;
  const double z = tick < 1000 ? top + (low - top) * double(tick) / 1000.0 : low;
  s.p_world = Eigen::Vector3d(test::kRigFloorX, 0.0, z);
  s.v_world = Eigen::Vector3d(0.0, 0.0, tick < 1000 ? (low - top) : 0.0);
  s.q_world = kLean;
  if (tick == 2000) s.valid = false;
}

srv::CapsuleToolConfig toolConfig() {
  scene::Tool tool;
  tool.shape = scene::ToolShape::Capsule;
  srv::RendererConfig renderer;
  renderer.stiffness_n_per_m = 600.0;
  renderer.damping_ns_per_m = 1.0;  // the shipped scenes'
  return srv::capsuleToolConfigFor(tool, renderer, 1e-3);
}

// The servo fixture's V-valley rig, its device `spec`, rendering a capsule.
struct CapsuleRig : test::ServoRigInputs {
  CapsuleRig(const dev::DeviceSpec& spec, test::FakeDevice::Script script)
      : test::ServoRigInputs(script), device6(std::move(script), 100000, spec),
        tool(*texture.surface, spec, toolConfig()),
        rig(device6, *texture.surface, test::unitTestWiring(600.0), nullptr, &tool) {}
  test::FakeDevice device6;
  srv::CapsuleTool tool;
  srv::ServoRig rig;
};

}  // namespace

TEST(ServoCapsule, ASixDofDeviceGetsTheToolsForceAndTorqueThroughTheSafetyStage) {
  CapsuleRig c(dev::simulated6DofSpec(), pressIntoTheValley);
  double largest_torque = 0.0, largest_penetration = 0.0;
  int ramping_with_torque = 0;
  for (int k = 0; k < 3000; ++k) {
    const srv::TickRecord& r = c.rig.tickAndDrain();
    const Eigen::Vector3d tau_render = v3(r.tau_render), tau_out = v3(r.tau_out);
    // What the device was told is the record's, force and torque.
    ASSERT_EQ(c.device6.writes().back(), v3(r.f_out)) << k;
    ASSERT_EQ(c.device6.torqueWrites().back(), tau_out) << k;
    if (!r.valid) {  // nothing acts on a pen whose pose is unknown, the torque neither
      EXPECT_FALSE(r.tool);
      EXPECT_EQ(tau_out, Eigen::Vector3d::Zero());
      EXPECT_EQ(v3(r.f_out), Eigen::Vector3d::Zero());
      continue;
    }
    ASSERT_TRUE(r.tool) << k;
    // The torque follows the force's safety gain (its engage ramp), the scene's gain being 1.
    const double gain = c.rig.safety().gain();
    const bool passing = !(r.safety_flags & (srv::kSafetyDisengaged | srv::kSafetyShutDown));
    EXPECT_LT((tau_out - (passing ? gain : 0.0) * tau_render).norm(), 1e-15) << k;
    if (passing && gain > 0.0 && gain < 1.0 && tau_render.norm() > 0.0) ++ramping_with_torque;
    EXPECT_LE(tau_out.norm(), dev::simulated6DofSpec().peak_torque_nm + 1e-12);
    // After the invalid reading the tool starts again from above the relief (a god object never
    // starts inside) and lands within ten ticks.
    if (k >= 1500 && (k < 2000 || k >= 2010)) {
      largest_torque = std::max(largest_torque, tau_out.norm());
      largest_penetration = std::max(largest_penetration, r.tool_penetration_m);
      EXPECT_TRUE(r.in_contact) << k;
      EXPECT_GT(r.f_out[2], 0.0) << k;  // held up out of the valley
      // The tip's ball rests on the walls above the device's tip; the record's proxy is its centre.
      EXPECT_GT(r.proxy_world[2], r.p_world[2] + 0.002) << k;
    }
  }
  std::printf("[measured] lean into a V-valley: torque up to %.4f N m, tool penetration up to %.2e m\n",
              largest_torque, largest_penetration);
  EXPECT_GT(largest_torque, 1e-3);  // the tool pivots on its tip: a lever the device feels
  EXPECT_LT(largest_penetration, 1e-5);
  EXPECT_GT(ramping_with_torque, 0);  // the ramp was seen with a torque to scale
  EXPECT_EQ(c.rig.servo().counters().faults, 0u);  // one invalid reading is not a fault
}

TEST(ServoCapsule, AForceOnlyDeviceGetsTheForceAndNoTorque) {
  CapsuleRig c(dev::phantomDesktopSpec(), pressIntoTheValley);
  double largest_force = 0.0;
  for (int k = 0; k < 2000; ++k) {
    const srv::TickRecord& r = c.rig.tickAndDrain();
    EXPECT_EQ(v3(r.tau_render), Eigen::Vector3d::Zero()) << k;
    EXPECT_EQ(c.device6.torqueWrites().back(), Eigen::Vector3d::Zero()) << k;
    largest_force = std::max(largest_force, v3(r.f_out).norm());
  }
  EXPECT_GT(largest_force, 0.5);
}

TEST(ServoCapsule, NothingInTheCapsulesTickAllocates) {
  CapsuleRig c(dev::simulated6DofSpec(), [](std::int64_t tick, dev::DeviceState& s) {
    // Press the leaning pen into a valley, stroke it across five valleys and back, lift it.
    pressIntoTheValley(tick % 1000, s);
    const double t = double(tick) / 1000.0;
    if (t >= 1.0) s.p_world = Eigen::Vector3d(0.02 * std::sin((t - 1.0) * 2.0), 0.001 * t, t < 3.5 ? -0.0045 : 0.002);
    s.valid = tick != 2000;
  });
  c.rig.servo().publishSnapshots();
  c.rig.tickAndDrain();
  const long before = test::g_allocations.load();
  for (int k = 0; k < 4000; ++k) c.rig.tickAndDrain();
  EXPECT_EQ(test::g_allocations.load() - before, 0);
  EXPECT_GT(c.rig.servo().counters().contact_ticks, 1500u);
}

// A scene switch takes the tool away (the plane's point pen renders the same surface) and gives it
// back; the servo neither allocates nor frees doing it.
TEST(ServoCapsule, ASceneSwitchTakesTheToolAndGivesItBack) {
  CapsuleRig c(dev::simulated6DofSpec(), pressIntoTheValley);
  for (int k = 0; k < 1500; ++k) c.rig.tickAndDrain();
  srv::SurfaceSwap point;
  point.surface = c.texture.surface.get();
  point.renderer.stiffness_n_per_m = 600.0;
  point.stored_energy_stiffness_n_per_m = 600.0;
  srv::SurfaceSwap capsule = point;
  capsule.tool = &c.tool;
  const long allocations = test::t_allocations, frees = test::t_frees;
  ASSERT_TRUE(c.rig.servo().surfaceSwap().offer(&point));
  for (int k = 0; k < 600; ++k) c.rig.tickAndDrain();  // ramps of 200 ticks down and up
  EXPECT_EQ(c.rig.servo().capsuleTool(), nullptr);
  const srv::TickRecord& on_point = c.rig.tickAndDrain();
  EXPECT_FALSE(on_point.tool);
  EXPECT_TRUE(on_point.in_contact);  // the point pen, in the valley
  EXPECT_EQ(v3(on_point.tau_out), Eigen::Vector3d::Zero());
  c.rig.servo().surfaceSwap().reclaim();
  ASSERT_TRUE(c.rig.servo().surfaceSwap().offer(&capsule));
  for (int k = 0; k < 1200; ++k) c.rig.tickAndDrain();
  EXPECT_EQ(c.rig.servo().capsuleTool(), &c.tool);
  const srv::TickRecord& on_tool = c.rig.tickAndDrain();
  EXPECT_TRUE(on_tool.tool);
  EXPECT_TRUE(on_tool.in_contact);
  EXPECT_GT(v3(on_tool.tau_out).norm(), 1e-3);
  EXPECT_EQ(test::t_allocations - allocations, 0);
  EXPECT_EQ(test::t_frees - frees, 0);
  EXPECT_EQ(c.rig.servo().counters().faults, 0u);
}

namespace {

// The default scene (scenes/default.yaml: bricks, a stroke and a press) with `tool` under its
// device, wired as hapticd wires it.
struct DefaultSceneWith {
  DefaultSceneWith(const test::TempDir& dir, const std::string& tool, const srv::ScenePolicy& policy = {}) {
    std::ifstream in(std::string(THX_SOURCE_DIR) + "/scenes/default.yaml");
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    text.replace(text.find("\ndevice:\n"), 9, "\ndevice:\n  tool: " + tool + "\n");
    path = dir.file("default_capsule.yaml");
    std::ofstream(path) << text;
    sc = scene::loadScene(path);
    device = srv::makeSceneDevice(sc, "", "", /*lockstep=*/true);
    prepared = srv::prepareScene(sc, path, {device.device->spec()}, policy);
  }
  std::string path;
  scene::Scene sc;
  srv::SceneDevice device;
  std::unique_ptr<srv::PreparedScene> prepared;
};

}  // namespace

TEST(ServoCapsule, TheDefaultScenesStrokeAndPressHoldTheCapsuleOutOfTheBricks) {
  test::TempDir dir("servo_capsule");
  DefaultSceneWith s(dir, "{shape: capsule, length: 0.1, radius: 0.002}");
  ASSERT_NE(s.prepared->devices[0].tool, nullptr);
  EXPECT_EQ(s.prepared->devices[0].swap.tool, s.prepared->devices[0].tool.get());
  srv::ServoRig rig(*s.device.device, s.prepared->surface.surface, s.prepared->devices[0].wiring, nullptr,
                    s.prepared->devices[0].tool.get());
  s.device.device->open();
  const auto ticks = std::int64_t((s.device.sim->script().duration() + 0.3) * s.sc.rates.servo_hz);
  double deepest = 0.0, largest = 0.0;
  std::int64_t contact = 0;
  for (std::int64_t k = 0; k < ticks; ++k) {
    const srv::TickRecord& r = rig.tickAndDrain();
    ASSERT_TRUE(r.tool);
    deepest = std::max(deepest, r.tool_penetration_m);
    largest = std::max(largest, v3(r.f_out).norm());
    contact += r.in_contact;
  }
  s.device.device->close();
  std::printf("[measured] default scene with a capsule: %lld ticks, %lld in contact, deepest %.1f um, largest force %.2f N,"
              " passivity controller active %llu ticks\n",
              (long long)ticks, (long long)contact, deepest * 1e6, largest, (unsigned long long)rig.passivity().activeTicks());
  EXPECT_EQ(rig.servo().counters().faults, 0u);
  EXPECT_GT(contact, ticks / 2);
  EXPECT_LT(deepest, 2e-4);  // the ball at brick corners is left a few tens of um in (docs/hapticd.md)
  EXPECT_LT(largest, 7.9);   // the desktop's peak: never clamped
}

TEST(ServoCapsule, ACapsuleIsRefusedWhereItCannotBeRendered) {
  test::TempDir dir("servo_capsule_refused");
  srv::ScenePolicy paper;
  paper.paper_loop_plane_hz = 100.0;
  EXPECT_NE(test::errorOf([&] { DefaultSceneWith s(dir, "{shape: capsule}", paper); })
                .find("device.tool: capsule: --paper-loop renders the point pen"),
            std::string::npos);
  srv::ScenePolicy planes;
  planes.device_renders_planes = true;
  EXPECT_NE(test::errorOf([&] { DefaultSceneWith s(dir, "{shape: capsule}", planes); })
                .find("the device renders the plane proxies it is sent"),
            std::string::npos);
  // The point pen is fine with either.
  EXPECT_EQ(test::errorOf([&] { DefaultSceneWith s(dir, "{shape: point}", planes); }), "<no thx::Error>");
}

}  // namespace test_servo_capsule
