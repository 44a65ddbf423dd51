// Non-fatal issues: the scene loads, and Scene::warnings says what is probably wrong and where.
#include <gtest/gtest.h>

#include "scenes/scene_loader.hpp"

namespace test_scene_warnings {

namespace {

using namespace thx::scene;

std::string sceneWith(const std::string& surface_extra, const std::string& rest = "",
                      const std::string& texture = "{generator: bricks, size: 16}",
                      const std::string& size = "[0.2, 0.2]") {
  return "version: 1\nname: w\nsurface:\n  size: " + size + "\n  texture: " + texture + "\n" + surface_extra + rest;
}

// Exactly one warning, containing every part.
void expectOneWarning(const std::string& text, const std::vector<std::string>& parts) {
  const Scene s = parseScene(text, "w.yaml", "");
  ASSERT_EQ(s.warnings.size(), 1u) << (s.warnings.empty() ? std::string("none") : s.warnings.front());
  for (const std::string& part : parts)
    EXPECT_NE(s.warnings[0].find(part), std::string::npos) << "'" << part << "' not in: " << s.warnings[0];
}

TEST(SceneWarnings, CleanSceneHasNone) { EXPECT_TRUE(parseScene(sceneWith(""), "w.yaml", "").warnings.empty()); }

TEST(SceneWarnings, ExtentDifferentFromSurfaceSize) {
  expectOneWarning(sceneWith("", "", "{generator: bricks, size: 16, params: {extent: 0.1}}"),
                   {"w.yaml:5:", "surface.texture.params.extent", "extent 0.1 m differs from surface.size 0.2 m"});
}

TEST(SceneWarnings, GeneratedTextureOnNonSquareSurface) {
  expectOneWarning(sceneWith("", "", "{generator: bricks, size: 16}", "[0.2, 0.1]"),
                   {"surface.texture.generator", "stretched"});
}

TEST(SceneWarnings, MaxDepthWithNormalRepresentation) {
  expectOneWarning(sceneWith("  representation: normal\n  max_depth: 0.002\n"),
                   {"w.yaml:7:", "surface.max_depth", "ignored for representation: normal"});
}

TEST(SceneWarnings, MaxDepthFractionWithNormalRepresentation) {
  expectOneWarning(sceneWith("  representation: normal\n  max_depth_fraction: 0.01\n"),
                   {"w.yaml:7:", "surface.max_depth_fraction", "ignored for representation: normal"});
}

TEST(SceneWarnings, GreenWithGeneratedTexture) {
  expectOneWarning(sceneWith("  green: directx\n"), {"surface.green", "ignored for generated textures"});
}

TEST(SceneWarnings, ForceAboveContinuousButBelowPeak) {
  expectOneWarning(sceneWith("", "device:\n  script:\n    - press: {position: [0, 0], force: 5, duration: 1}\n"),
                   {"device.script[0].press.force", "above the continuous force", "1.185 N"});
}

TEST(SceneWarnings, ScriptBeyondTheWorkspace) {
  expectOneWarning(sceneWith("",
                             "device:\n  model: touch\n  script:\n"
                             "    - press: {position: [0.09, 0.09], force: 0.4, duration: 1}\n"),
                   {"device.script", "beyond the touch workspace radius 0.075 m"});
}

TEST(SceneWarnings, ObjectBelowTheSurface) {
  expectOneWarning(
      sceneWith("", "objects:\n  - {name: sunk, shape: sphere, radius: 0.01, mass: 0.03, position: [0, 0, -0.02]}\n"),
      {"objects[0].position", "'sunk' starts 0.02 m below the surface plane"});
}

TEST(SceneWarnings, IntegrationRateNotAMultipleOfServoRate) {
  expectOneWarning(sceneWith("", "device:\n  sim: {integration_hz: 15000}\nrates: {servo_hz: 2000}\n"),
                   {"device.sim.integration_hz", "not a multiple of rates.servo_hz"});
}

TEST(SceneWarnings, ZeroStiffness) {
  expectOneWarning(sceneWith("", "device:\n  stiffness_fraction: 0\n"), {"renders no force"});
}

TEST(SceneWarnings, AudioFedFasterThanTheServo) {
  expectOneWarning(sceneWith("", "rates: {audio_feed_hz: 2000}\n"), {"rates.audio_feed_hz", "above servo_hz"});
}

}  // namespace

}  // namespace test_scene_warnings
