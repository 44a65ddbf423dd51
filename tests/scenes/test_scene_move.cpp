// device.script's move step (issue 30, docs/scenes.md "device.script"): the hand anywhere above the
// surface with a push any way; refused where its heights mean nothing (a mesh), outside the hand's
// room, or pushing beyond the device's peak force.
#include <gtest/gtest.h>

#include <string>
#include <variant>
#include <vector>

#include "scenes/scene_loader.hpp"
#include "tests/scenes/scene_error_of.hpp"

namespace test_scene_move {

namespace {

using namespace thx::scene;

const std::string kPlane = thx::test::planeSceneText("move");
const auto& errorOf = thx::test::sceneErrorOf;

}  // namespace

TEST(SceneMove, AMoveIsAPointAboveTheSurfaceAndAPush) {
  const Scene s = parseScene(kPlane + "device:\n  script:\n    - move: {to: [0.01, -0.02, 0.03], push: [-1.5, 0, 0.5], "
                                      "duration: 0.8}\n    - move: {to: [0.01, -0.02, 0.05], duration: 1}\n",
                             "s.yaml", "");
  ASSERT_EQ(s.device.script.size(), 2u);
  const auto* grip = std::get_if<MoveStep>(&s.device.script[0]);
  ASSERT_NE(grip, nullptr);
  EXPECT_EQ(grip->to_m, Eigen::Vector3d(0.01, -0.02, 0.03));
  EXPECT_EQ(grip->push_n, Eigen::Vector3d(-1.5, 0.0, 0.5));
  EXPECT_DOUBLE_EQ(grip->duration_s, 0.8);
  const auto* lift = std::get_if<MoveStep>(&s.device.script[1]);
  ASSERT_NE(lift, nullptr);
  EXPECT_EQ(lift->push_n, Eigen::Vector3d::Zero());  // no push unless given
}

TEST(SceneMove, AMoveThatDoesNotFitIsRefusedNamingTheField) {
  struct Case {
    std::string text;
    std::vector<std::string> contains;
  };
  const std::string mesh = "version: 1\nname: move\nsurface:\n  size: [0.02, 0.02]\n"
                           "  mesh: {generator: plate, size: 0.02, segments: 8}\n  texture: {generator: bricks}\n";
  const std::vector<Case> cases = {
      {kPlane + "device:\n  script:\n    - move: {to: [0.3, 0, 0.01], duration: 1}\n",
       {"device.script[0].move.to", "outside the hand's room", "z in [-0.05, 0.3] m", "got [0.3, 0, 0.01]"}},
      {kPlane + "device:\n  script:\n    - move: {to: [0, 0, 0.5], duration: 1}\n",
       {"device.script[0].move.to", "outside the hand's room"}},
      {kPlane + "device:\n  script:\n    - move: {to: [0, 0, 0.01], push: [6, 6, 0], duration: 1}\n",
       {"device.script[0].move.push", "push above the peak force of phantom_desktop", "at most 7.9 N"}},
      {kPlane + "device:\n  script:\n    - move: {to: [0, 0, 0.01]}\n", {"device.script[0].move.duration", "missing"}},
      {kPlane + "device:\n  script:\n    - move: {to: [0, 0, 0.01], duration: 1, speed: 2}\n",
       {"device.script[0].move.speed", "unknown field"}},
      {mesh + "device:\n  script:\n    - move: {to: [0, 0, 0.01], duration: 1}\n",
       {"device.script[0].move", "a move needs a plane surface"}},
  };
  for (const Case& c : cases) {
    const std::string message = errorOf(c.text);
    ASSERT_FALSE(message.empty()) << c.text;
    for (const std::string& part : c.contains) EXPECT_NE(message.find(part), std::string::npos) << message;
  }
}

}  // namespace test_scene_move
