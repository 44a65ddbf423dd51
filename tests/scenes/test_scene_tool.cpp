// device.tool (issue 30, docs/scenes.md): the point pen by default, a capsule when asked, and every
// field that does not fit the device or the surface refused naming the field.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "scenes/scene_loader.hpp"
#include "tests/scenes/scene_error_of.hpp"

namespace test_scene_tool {

namespace {

using namespace thx::scene;

const std::string kPlane = thx::test::planeSceneText("tool");
const auto& errorOf = thx::test::sceneErrorOf;

}  // namespace

TEST(SceneTool, ThePenIsAPointUnlessTheSceneSaysCapsule) {
  const Scene point = parseScene(kPlane, "s.yaml", "");
  EXPECT_EQ(point.device.tool.shape, ToolShape::Point);

  const Scene capsule = parseScene(
      kPlane + "device:\n  tool: {shape: capsule, length: 0.12, radius: 0.003, rot_stiffness: 0.8}\n", "s.yaml", "");
  EXPECT_EQ(capsule.device.tool.shape, ToolShape::Capsule);
  EXPECT_DOUBLE_EQ(capsule.device.tool.length_m, 0.12);
  EXPECT_DOUBLE_EQ(capsule.device.tool.radius_m, 0.003);
  EXPECT_DOUBLE_EQ(capsule.device.tool.rot_stiffness_nm_per_rad, 0.8);

  const Scene defaults = parseScene(kPlane + "device:\n  tool: {shape: capsule}\n", "s.yaml", "");
  EXPECT_DOUBLE_EQ(defaults.device.tool.length_m, 0.10);
  EXPECT_DOUBLE_EQ(defaults.device.tool.radius_m, 0.002);

  const Scene two = parseScene(kPlane + "devices:\n  - {name: a}\n  - {name: b, tool: {shape: capsule}}\n", "s.yaml", "");
  EXPECT_EQ(deviceAt(two, 0).tool.shape, ToolShape::Point);
  EXPECT_EQ(deviceAt(two, 1).tool.shape, ToolShape::Capsule);
}

TEST(SceneTool, AToolThatDoesNotFitIsRefusedNamingTheField) {
  struct Case {
    std::string text;
    std::vector<std::string> contains;
  };
  const std::string mesh_surface =
      "version: 1\nname: tool\nsurface:\n  size: [0.02, 0.02]\n  mesh: {generator: plate, size: 0.02, segments: 8}\n"
      "  texture: {generator: bricks}\n";
  const std::vector<Case> cases = {
      {kPlane + "device:\n  tool: {shape: cone}\n", {"device.tool.shape", "one of: point, capsule", "got 'cone'"}},
      {kPlane + "device:\n  tool: {length: 0.1}\n", {"device.tool.length", "applies only to shape: capsule"}},
      {kPlane + "device:\n  tool: {shape: capsule, radius: 0.02}\n", {"device.tool.radius", "(0, 0.01] m", "got '0.02'"}},
      {kPlane + "device:\n  tool: {shape: capsule, length: 0.003, radius: 0.002}\n",
       {"device.tool", "shorter than it is wide", "length >= 2 x radius"}},
      {kPlane + "device:\n  tool: {shape: capsule, rot_stiffness: -1}\n", {"device.tool.rot_stiffness", "[0, 10] N·m/rad"}},
      {kPlane + "device:\n  tool: {shape: capsule, mass: 1}\n", {"device.tool.mass", "unknown field"}},
      {kPlane + "device:\n  type: vrpn\n  address: Phantom0@localhost\n  tool: {shape: capsule}\n",
       {"device.tool.shape", "applies only to type: sim", "renders the plane proxies"}},
      {"version: 1\nname: tool\nsurface:\n  size: [0.2, 0.2]\n  texture: {generator: bricks}\n  representation: normal\n"
       "device:\n  tool: {shape: capsule}\n",
       {"device.tool.shape", "needs a relief (surface.representation: relief)"}},
      {mesh_surface + "device:\n  tool: {shape: capsule}\n",
       {"device.tool.shape", "applies only to a textured plane", "surface.mesh"}},
  };
  for (const Case& c : cases) {
    const std::string message = errorOf(c.text);
    ASSERT_FALSE(message.empty()) << c.text;
    for (const std::string& part : c.contains) EXPECT_NE(message.find(part), std::string::npos) << message;
  }
}

}  // namespace test_scene_tool
