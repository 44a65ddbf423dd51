// The scenes shipped in scenes/ load cleanly, say what their comments say, and their textures
// can be built from exactly the parameters they give.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>

#include "scenes/scene_loader.hpp"
#include "scenes/surface_texture.hpp"

namespace test_shipped_scenes {

namespace {

using namespace thx::scene;

const std::string kScenes = std::string(THX_SOURCE_DIR) + "/scenes/";

std::string joined(const std::vector<std::string>& lines) {
  std::string s;
  for (const std::string& l : lines) s += l + "\n";
  return s;
}

// Generating the full-size maps is the generators' tests' business; here a small map shows
// that the shipped parameters are accepted by generate().
void expectTextureBuilds(Scene scene) {
  scene.surface.texture.generator.size = 32;
  const thx::tex::TextureMap map = buildSurfaceTexture(scene);
  EXPECT_EQ(map.width(), 32);
  EXPECT_EQ(map.isRelief(), scene.surface.representation == thx::tex::Representation::Relief);
}

TEST(ShippedScenes, EveryYamlLoadsWithoutWarnings) {
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(kScenes)) {
    if (entry.path().extension() != ".yaml") continue;
    ++count;
    const Scene scene = loadScene(entry.path().string());
    EXPECT_TRUE(scene.warnings.empty()) << entry.path() << ":\n" << joined(scene.warnings);
    EXPECT_FALSE(scene.name.empty());
  }
  EXPECT_GE(count, 2);
}

TEST(ShippedScenes, DefaultIsBricksUnderASimulatedDesktop) {
  const Scene s = loadScene(kScenes + "default.yaml");
  EXPECT_EQ(s.version, 1);
  ASSERT_EQ(s.surface.texture.kind, TextureSource::Kind::Generator);
  EXPECT_EQ(s.surface.texture.generator.kind, "bricks");
  EXPECT_EQ(s.surface.representation, thx::tex::Representation::Relief);
  EXPECT_EQ(s.surface.texture.generator.params.at("extent"), s.surface.size_m.x());
  EXPECT_EQ(s.surface.size_m.x(), s.surface.size_m.y());
  EXPECT_EQ(s.surface.material.name, "brick");

  EXPECT_EQ(s.device.type, DeviceType::Sim);
  EXPECT_EQ(s.device.model.name, "phantom_desktop");
  EXPECT_DOUBLE_EQ(s.device.stiffness_fraction, 0.6);
  EXPECT_DOUBLE_EQ(s.device.stiffnessNPerM(), 600.0);

  // A stroke across the bricks comes before a press.
  std::ptrdiff_t stroke = -1, press = -1;
  for (std::size_t i = 0; i < s.device.script.size(); ++i) {
    if (std::holds_alternative<StrokeStep>(s.device.script[i]) && stroke < 0) stroke = std::ptrdiff_t(i);
    if (std::holds_alternative<PressStep>(s.device.script[i])) press = std::ptrdiff_t(i);
  }
  ASSERT_GE(stroke, 0);
  EXPECT_GT(press, stroke);
  const auto& st = std::get<StrokeStep>(s.device.script[std::size_t(stroke)]);
  const double brick_length = s.surface.texture.generator.params.at("brick_length");
  EXPECT_GT(std::fabs(st.to_m.x() - st.from_m.x()), 2.0 * brick_length) << "the stroke should cross several bricks";

  ASSERT_EQ(s.objects.size(), 1u);
  const SceneObject& marble = s.objects[0];
  EXPECT_EQ(marble.name, "marble");
  EXPECT_EQ(marble.shape, Shape::Sphere);
  EXPECT_EQ(marble.material.name, "glass");
  const double expected_mass =
      marble.material.density_kg_per_m3 * 4.0 / 3.0 * std::numbers::pi * std::pow(marble.radius_m, 3);
  EXPECT_NEAR(marble.mass_kg, expected_mass, 0.01 * expected_mass);
  EXPECT_GT(marble.pose.position_m.z(), marble.radius_m) << "the marble starts above the surface";
}

TEST(ShippedScenes, DefaultTextureBuilds) { expectTextureBuilds(loadScene(kScenes + "default.yaml")); }

TEST(ShippedScenes, VValleyPressesIntoAValleyFloor) {
  const Scene s = loadScene(kScenes + "vvalley.yaml");
  const auto& g = s.surface.texture.generator;
  EXPECT_EQ(g.kind, "vvalley");
  EXPECT_EQ(g.params.at("angle_deg"), 60.0);
  EXPECT_EQ(g.params.at("extent"), s.surface.size_m.x());

  const PressStep* press = nullptr;
  for (const ScriptStep& step : s.device.script)
    if (const auto* p = std::get_if<PressStep>(&step)) press = p;
  ASSERT_NE(press, nullptr);
  // Ridges at texture x = k * period, floors half way; surface-local x = texture x - extent / 2.
  const double period = g.params.at("period");
  const double texture_x = press->position_m.x() + g.params.at("extent") / 2.0;
  const double phase = texture_x / period - std::floor(texture_x / period);
  EXPECT_NEAR(phase, 0.5, 1e-9);
}

TEST(ShippedScenes, VValleyTextureBuilds) { expectTextureBuilds(loadScene(kScenes + "vvalley.yaml")); }

}  // namespace

}  // namespace test_shipped_scenes
