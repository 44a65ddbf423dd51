// What a minimal scene turns into, and that every written value arrives where it belongs.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "scenes/scene_loader.hpp"

namespace test_scene_defaults {

namespace {

using namespace thx::scene;

const std::string kMinimal = R"(version: 1
name: minimal
surface:
  size: [0.2, 0.2]
  texture: {generator: bricks}
)";

TEST(SceneDefaults, MinimalSceneGetsEveryDefault) {
  const Scene s = parseScene(kMinimal, "minimal.yaml", "");
  EXPECT_TRUE(s.warnings.empty());
  EXPECT_EQ(s.source, "minimal.yaml");
  EXPECT_EQ(s.description, "");

  const Surface& surface = s.surface;
  EXPECT_EQ(surface.pose.position_m, Eigen::Vector3d::Zero());
  EXPECT_EQ(surface.pose.rpy_deg, Eigen::Vector3d::Zero());
  EXPECT_EQ(surface.texture.kind, TextureSource::Kind::Generator);
  EXPECT_EQ(surface.texture.generator.size, 512);
  EXPECT_EQ(surface.texture.generator.seed, 1u);
  // The extent is filled from the surface so the texture spans it once.
  ASSERT_EQ(surface.texture.generator.params.size(), 1u);
  EXPECT_EQ(surface.texture.generator.params.at("extent"), 0.2);
  EXPECT_EQ(surface.representation, thx::tex::Representation::Relief);
  EXPECT_FALSE(surface.max_depth_m.has_value());
  EXPECT_EQ(surface.green, thx::tex::GreenConvention::OpenGL);
  EXPECT_EQ(surface.sampling.filter, thx::tex::Filter::Bilinear);
  EXPECT_EQ(surface.sampling.address, thx::tex::Address::Wrap);
  EXPECT_EQ(surface.material.name, "ceramic");
  EXPECT_EQ(surface.smoothing_sigma_texels, 0.0);

  const Device& d = s.device;
  EXPECT_EQ(d.type, DeviceType::Sim);
  EXPECT_EQ(d.model.name, "phantom_desktop");
  EXPECT_EQ(d.address, "");
  EXPECT_EQ(d.stiffness_fraction, 0.5);
  EXPECT_EQ(d.damping_ns_per_m, 0.0);
  const SimDeviceParams defaults;
  EXPECT_EQ(d.sim.integration_hz, defaults.integration_hz);
  EXPECT_GE(d.sim.integration_hz, 10000);
  EXPECT_EQ(d.sim.encoder_resolution_m, defaults.encoder_resolution_m);
  EXPECT_EQ(d.sim.device_mass_kg, defaults.device_mass_kg);
  EXPECT_EQ(d.sim.hand_stiffness_n_per_m, defaults.hand_stiffness_n_per_m);
  EXPECT_TRUE(d.script.empty());

  EXPECT_TRUE(s.objects.empty());
  EXPECT_EQ(s.rates.servo_hz, 1000);
  EXPECT_EQ(s.rates.physics_hz, 1000);
  EXPECT_EQ(s.rates.visual_hz, 60);
  EXPECT_EQ(s.rates.audio_hz, 44100);
  EXPECT_EQ(s.rates.audio_feed_hz, 1000);
}

TEST(SceneDefaults, EmptySectionsReadAsEmpty) {
  const Scene s = parseScene(kMinimal + "device:\nobjects:\nrates:\n", "m.yaml", "");
  EXPECT_TRUE(s.objects.empty());
  EXPECT_EQ(s.device.type, DeviceType::Sim);
  EXPECT_EQ(s.rates.servo_hz, 1000);
}

TEST(SceneDefaults, ObjectDefaults) {
  const Scene s = parseScene(kMinimal + R"(objects:
  - {name: ball, shape: sphere, radius: 0.01, mass: 0.03, position: [0, 0, 0.05]}
)",
                             "m.yaml", "");
  ASSERT_EQ(s.objects.size(), 1u);
  EXPECT_EQ(s.objects[0].material.name, "steel");
  EXPECT_EQ(s.objects[0].velocity_m_per_s, Eigen::Vector3d::Zero());
  EXPECT_EQ(s.objects[0].pose.rpy_deg, Eigen::Vector3d::Zero());
}

TEST(SceneValues, EveryWrittenValueArrives) {
  const Scene s = parseScene(R"(version: 1
name: everything
description: all fields
surface:
  size: [0.3, 0.3]
  pose: {position: [0.01, -0.02, 0.03], rpy_deg: [1, 2, 3]}
  texture:
    generator: vvalley
    size: 64
    seed: 18446744073709551615
    params: {angle_deg: 60, period: 0.005, extent: 0.3}
  representation: normal
  sampling: {filter: nearest, address: clamp}
  material: polycarbonate
  smoothing_sigma: 1.5
device:
  type: vrpn
  model: premium_3_0
  address: Phantom0@tcp://lab-pc:3883
  stiffness_fraction: 0.25
  damping: 2
objects:
  - {name: pill, shape: capsule, radius: 0.005, length: 0.02, mass: 0.01, material: plastic,
     position: [0, 0, 0.05], rpy_deg: [90, 0, 0], velocity: [0.1, 0, 0]}
  - {name: crate, shape: box, size: [0.02, 0.03, 0.04], mass: 0.2, material: wood, position: [0.05, 0, 0.05]}
  - {name: can, shape: cylinder, radius: 0.01, length: 0.03, mass: 0.02, material: tin, position: [-0.05, 0, 0.05]}
rates: {servo_hz: 2000, physics_hz: 500, visual_hz: 30, audio_hz: 48000, audio_feed_hz: 500}
)",
                             "all.yaml", "");
  EXPECT_TRUE(s.warnings.empty()) << (s.warnings.empty() ? "" : s.warnings.front());
  EXPECT_EQ(s.description, "all fields");
  EXPECT_EQ(s.surface.size_m, Eigen::Vector2d(0.3, 0.3));
  EXPECT_EQ(s.surface.pose.position_m, Eigen::Vector3d(0.01, -0.02, 0.03));
  EXPECT_EQ(s.surface.pose.rpy_deg, Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(s.surface.texture.generator.kind, "vvalley");
  EXPECT_EQ(s.surface.texture.generator.size, 64);
  EXPECT_EQ(s.surface.texture.generator.seed, 18446744073709551615u);
  EXPECT_EQ(s.surface.texture.generator.params.at("period"), 0.005);
  EXPECT_EQ(s.surface.representation, thx::tex::Representation::Normal);
  EXPECT_EQ(s.surface.sampling.filter, thx::tex::Filter::Nearest);
  EXPECT_EQ(s.surface.sampling.address, thx::tex::Address::Clamp);
  EXPECT_EQ(s.surface.material.name, "polycarbonate");
  EXPECT_EQ(s.surface.smoothing_sigma_texels, 1.5);

  EXPECT_EQ(s.device.type, DeviceType::Vrpn);
  EXPECT_EQ(s.device.model.name, "premium_3_0");
  EXPECT_EQ(s.device.model.peak_force_n, 22.0);
  EXPECT_EQ(s.device.address, "Phantom0@tcp://lab-pc:3883");
  EXPECT_DOUBLE_EQ(s.device.stiffnessNPerM(), 250.0);
  EXPECT_EQ(s.device.damping_ns_per_m, 2.0);

  ASSERT_EQ(s.objects.size(), 3u);
  EXPECT_EQ(s.objects[0].shape, Shape::Capsule);
  EXPECT_EQ(s.objects[0].length_m, 0.02);
  EXPECT_EQ(s.objects[0].pose.rpy_deg, Eigen::Vector3d(90, 0, 0));
  EXPECT_EQ(s.objects[0].velocity_m_per_s, Eigen::Vector3d(0.1, 0, 0));
  EXPECT_EQ(s.objects[1].shape, Shape::Box);
  EXPECT_EQ(s.objects[1].size_m, Eigen::Vector3d(0.02, 0.03, 0.04));
  EXPECT_EQ(s.objects[2].shape, Shape::Cylinder);
  EXPECT_EQ(s.objects[2].material.name, "tin");

  EXPECT_EQ(s.rates.servo_hz, 2000);
  EXPECT_EQ(s.rates.physics_hz, 500);
  EXPECT_EQ(s.rates.visual_hz, 30);
  EXPECT_EQ(s.rates.audio_hz, 48000);
  EXPECT_EQ(s.rates.audio_feed_hz, 500);
}

TEST(SceneValues, NumbersMayBeWrittenAsYamlAllows) {
  const Scene s = parseScene(kMinimal + R"(device:
  stiffness_fraction: "0.4"
  damping: +1.5
  sim: {integration_hz: 2e4, encoder_resolution: 1.0e-5, friction: 1e-400}
)",
                             "m.yaml", "");
  EXPECT_EQ(s.device.stiffness_fraction, 0.4);
  EXPECT_EQ(s.device.damping_ns_per_m, 1.5);
  EXPECT_EQ(s.device.sim.integration_hz, 20000);
  EXPECT_EQ(s.device.sim.encoder_resolution_m, 1e-5);
  EXPECT_EQ(s.device.sim.friction_n, 0.0);  // underflow is zero, not "not finite"
}

TEST(SceneValues, ScriptStepsInOrder) {
  const Scene s = parseScene(kMinimal + R"(device:
  script:
    - hold: {duration: 0.25}
    - stroke: {from: [-0.05, 0], to: [0.05, 0.01], speed: 0.02, force: 0.5}
    - press: {position: [0.01, 0.02], force: 0.8, duration: 2}
)",
                             "m.yaml", "");
  ASSERT_EQ(s.device.script.size(), 3u);
  EXPECT_EQ(std::get<HoldStep>(s.device.script[0]).duration_s, 0.25);
  const auto& stroke = std::get<StrokeStep>(s.device.script[1]);
  EXPECT_EQ(stroke.from_m, Eigen::Vector2d(-0.05, 0));
  EXPECT_EQ(stroke.to_m, Eigen::Vector2d(0.05, 0.01));
  EXPECT_EQ(stroke.speed_m_per_s, 0.02);
  EXPECT_EQ(stroke.force_n, 0.5);
  const auto& press = std::get<PressStep>(s.device.script[2]);
  EXPECT_EQ(press.position_m, Eigen::Vector2d(0.01, 0.02));
  EXPECT_EQ(press.duration_s, 2.0);
}

// Relative paths resolve against the scene's directory, not the working directory.
TEST(SceneValues, RelativePathsResolveAgainstTheSceneDirectory) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("thx_scene_paths_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir / "paths");
  std::ofstream(dir / "paths" / "circle.csv") << "# t_s, x_m, y_m, force_n\n0, 0, 0, 1\n";
  std::ofstream(dir / "scene.yaml") << kMinimal << "device:\n  script:\n    - path_file: paths/circle.csv\n";
  const Scene s = loadScene((dir / "scene.yaml").string());
  ASSERT_EQ(s.device.script.size(), 1u);
  EXPECT_EQ(std::filesystem::path(std::get<PathFileStep>(s.device.script[0]).path),
            (dir / "paths" / "circle.csv").lexically_normal());
  EXPECT_EQ(std::filesystem::path(s.base_dir), dir);
  std::filesystem::remove_all(dir);
}

TEST(SceneValues, FileTextureKeepsTheFilesRepresentationUnlessAsked) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("thx_scene_file_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "any.png") << "not checked at load time beyond existence";
  const std::string text = "version: 1\nname: f\nsurface:\n  size: [0.1, 0.1]\n  texture: {file: any.png}\n";
  const Scene s = parseScene(text, "f.yaml", dir.string());
  EXPECT_EQ(s.surface.texture.kind, TextureSource::Kind::File);
  EXPECT_EQ(std::filesystem::path(s.surface.texture.file), dir / "any.png");
  EXPECT_FALSE(s.surface.representation.has_value());
  std::filesystem::remove_all(dir);
}

}  // namespace

}  // namespace test_scene_defaults
