// A pen with extent in physics-client (issue 30): a scene device with `tool: capsule` gets that
// capsule as its pen, along the device's axis, so its shaft pushes objects; --pen-shape and
// friends, or a grasping pen, keep the pen standing on the tip along the plane's normal.
// Deterministic, no network: scenes/capsule_bricks.yaml with a steel ball added beside the tip.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include "clients/physics_client/options.hpp"
#include "clients/physics_client/physics_scene.hpp"
#include "scenes/scene_loader.hpp"
#include "tests/support/temp_dir.hpp"

namespace test_pen_tool {

namespace {

using namespace thx::physclient;

// capsule_bricks (a 100 mm shaft of 2 mm radius) with a 6 mm steel ball, resting 30 mm along +x of
// the tip, in place of its marble.
thx::scene::Scene capsuleSceneWithBall(const thx::test::TempDir& dir) {
  std::ifstream in(std::string(THX_SOURCE_DIR) + "/scenes/capsule_bricks.yaml");
  std::stringstream read;
  read << in.rdbuf();
  std::string text = read.str();
  const auto objects = text.find("\nobjects:\n"), rates = text.find("\nrates:");
  text.replace(objects, rates - objects,
               "\nobjects:\n  - {name: ball, shape: sphere, radius: 0.006, mass: 0.0071, material: steel, "
               "position: [0.03, 0.01, 0.0062]}\n");
  const std::string path = dir.file("capsule_ball.yaml");
  std::ofstream(path) << text;
  return thx::scene::loadScene(path);
}

struct Sweep {
  double ball_moved_m = 0.0;
  long long contact_steps = 0;
  double largest_force_n = 0.0;
};

// The ball settles (0.4 s, the pen parked); then the tip is held at the ball's height, 30 mm from
// it along -x, the pen lying level and swung about the vertical from pointing 60 degrees away from
// the ball to pointing at it (+x) over 0.5 s, then held 0.5 s: the lying 100 mm shaft sweeps into
// the ball sideways.
Sweep sweep(const PenOptions& pen) {
  const thx::test::TempDir dir("pen_tool");
  SimOptions so;
  so.pen = pen;
  PhysicsScene sim(capsuleSceneWithBall(dir), so);
  const double dt = 1e-3;
  for (int k = 0; k < 400; ++k) sim.step(dt);
  const Eigen::Vector3d start = sim.body(0).p_world;
  const Eigen::Quaterniond lying(Eigen::AngleAxisd(0.5 * M_PI, Eigen::Vector3d::UnitY()));  // +z to +x
  Sweep s;
  for (int k = 0; k < 1000; ++k) {
    const double w = std::min(1.0, k * dt / 0.5);
    const double yaw = -M_PI / 3.0 * (0.5 + 0.5 * std::cos(M_PI * w));
    sim.setPenTip(Eigen::Vector3d(0.0, start.y(), start.z()));
    sim.setPenOrientation(0, Eigen::Quaterniond(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ())) * lying);
    sim.step(dt);
    s.contact_steps += sim.penForce().in_contact;
    s.largest_force_n = std::max(s.largest_force_n, sim.penForce().sent_world.norm());
  }
  s.ball_moved_m = (sim.body(0).p_world - start).norm();
  return s;
}

}  // namespace

TEST(PenTool, ASceneCapsuleToolIsThePensBodyAlongTheDevicesAxis) {
  const thx::test::TempDir dir("pen_tool_body");
  const thx::scene::Scene sc = capsuleSceneWithBall(dir);
  const PhysicsScene sim(sc, SimOptions{});
  const PhysicsScene::PenBody b = sim.penBody(0);
  EXPECT_EQ(b.shape, PenShape::Capsule);
  EXPECT_TRUE(b.along_device);
  EXPECT_EQ(b.radius_m, sc.device.tool.radius_m);
  EXPECT_EQ(b.length_m, sc.device.tool.length_m);
  // The command line's pen wins, and a grasping pen stands on the tip.
  SimOptions own;
  own.pen = parseOptions({"--scene", "s", "--pen-shape", "sphere"}).pen;
  EXPECT_FALSE(PhysicsScene(sc, own).penBody(0).along_device);
  EXPECT_EQ(PhysicsScene(sc, own).penBody(0).shape, PenShape::Sphere);
  SimOptions grasp;
  grasp.pen.coupling_n_per_m = 300.0;
  EXPECT_FALSE(PhysicsScene(sc, grasp).penBody(0).along_device);
  // A point-pen scene: the pen of old.
  const PhysicsScene plain(thx::scene::loadScene(std::string(THX_SOURCE_DIR) + "/scenes/pen_pushes_ball.yaml"));
  EXPECT_FALSE(plain.penBody(0).along_device);
  EXPECT_EQ(plain.penBody(0).length_m, PenOptions{}.length_m);
}

TEST(PenTool, TheLyingShaftSweepsTheBallAsideTheUprightPenMissesIt) {
  const Sweep shaft = sweep(PenOptions{});
  PenOptions upright;
  upright.scene_tool = false;
  const Sweep point = sweep(upright);
  std::printf("[measured] lying shaft swung into the ball: ball moved %.2f mm, pen in contact %lld steps, largest "
              "force %.2f N; the pen standing on the tip: ball moved %.3f mm, %lld steps\n",
              shaft.ball_moved_m * 1e3, shaft.contact_steps, shaft.largest_force_n, point.ball_moved_m * 1e3,
              point.contact_steps);
  EXPECT_GT(shaft.ball_moved_m, 0.002);
  EXPECT_GT(shaft.contact_steps, 0);
  EXPECT_GT(shaft.largest_force_n, 0.0);
  EXPECT_LT(point.ball_moved_m, 5e-5);
  EXPECT_EQ(point.contact_steps, 0);
}

}  // namespace test_pen_tool
