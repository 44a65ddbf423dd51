// buildSceneSurface: the one way every program builds a scene's textured surface; its name and
// fingerprint (what hapticd announces in hello_t and clients compare).
#include <gtest/gtest.h>

#include <filesystem>
#include <map>

#include "scenes/scene_frames.hpp"
#include "scenes/scene_loader.hpp"
#include "scenes/scene_surface.hpp"
#include "textures/smoothing.hpp"
#include "textures/texture_fingerprint.hpp"

namespace test_scene_surface {

namespace {

using namespace thx;
using namespace thx::scene;

const std::string kScenes = std::string(THX_SOURCE_DIR) + "/scenes/";

TEST(SceneSurface, NameIsTheFileStem) {
  EXPECT_EQ(sceneName(loadScene(kScenes + "marble_bricks.yaml")), "marble_bricks");
  Scene s;
  s.source = "/elsewhere/lab.scenes/study_wood.v2.yaml";
  EXPECT_EQ(sceneName(s), "study_wood.v2");
}

TEST(SceneSurface, SameSceneSameFingerprint) {
  const SceneSurface a = buildSceneSurface(loadScene(kScenes + "default.yaml"));
  const SceneSurface b = buildSceneSurface(loadScene(kScenes + "default.yaml"));
  EXPECT_EQ(a.scene_name, "default");
  EXPECT_EQ(a.fingerprint, b.fingerprint);
  EXPECT_EQ(a.fingerprint, tex::textureFingerprint(a.surface));
}

TEST(SceneSurface, SurfaceIsTheScenesPlaneAndSampling) {
  const Scene scene = loadScene(kScenes + "zigzag_street.yaml");  // a tilted plane
  SceneSurface s = buildSceneSurface(scene);
  const SceneSurface moved = std::move(s);  // the surface keeps pointing at the map it owns
  EXPECT_EQ(&moved.surface.map(), moved.map.get());
  EXPECT_TRUE(moved.surface.mapping().plane_to_world.isApprox(planeMapping(scene.surface).plane_to_world));
  EXPECT_EQ(moved.surface.mapping().size_m, scene.surface.size_m);
  EXPECT_EQ(moved.surface.sampling().address, scene.surface.sampling.address);
  EXPECT_EQ(moved.surface.sampling().filter, scene.surface.sampling.filter);
  EXPECT_TRUE(moved.surface.usesRelief());
  EXPECT_FALSE(placeOnScenePlane(scene, *moved.map, false).usesRelief());  // the benchmarks' normal-map reading
}

TEST(SceneSurface, OtherSizeOrTextureFileGivesAnotherFingerprint) {
  Scene scene = loadScene(kScenes + "default.yaml");
  scene.surface.texture.generator.size = 64;
  const std::uint64_t small = buildSceneSurface(scene).fingerprint;
  scene.surface.texture.generator.size = 65;
  EXPECT_NE(buildSceneSurface(scene).fingerprint, small);
  scene.surface.texture.generator.size = 64;
  scene.surface.texture.generator.seed += 1;
  EXPECT_NE(buildSceneSurface(scene).fingerprint, small);
  scene.surface.texture.generator.seed -= 1;
  scene.surface.size_m *= 1.01;  // the same texels over a larger plane
  EXPECT_NE(buildSceneSurface(scene).fingerprint, small);

  // A texture file that changed under the same scene: one texel differs.
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "thx_scene_surface_test";
  std::filesystem::create_directories(dir);
  scene.surface.size_m /= 1.01;
  tex::TextureMap map = *buildSceneSurface(scene).map;
  tex::saveTexture((dir / "t.png").string(), map);
  const std::string yaml = "version: 1\nname: t\nsurface:\n  size: [0.2, 0.2]\n  texture: {file: t.png}\n";
  const Scene from_file = parseScene(yaml, (dir / "t.yaml").string(), dir.string());
  const std::uint64_t before = buildSceneSurface(from_file).fingerprint;
  EXPECT_EQ(buildSceneSurface(from_file).fingerprint, before);
  map.setNormal(5, 9, Eigen::Vector3f(0.2f, 0.1f, 1.0f));
  tex::saveTexture((dir / "t.png").string(), map);
  EXPECT_NE(buildSceneSurface(from_file).fingerprint, before);
  std::filesystem::remove_all(dir);
}

// default and marble_bricks describe the same surface (bricks, seed 7, same parameters; their
// materials differ, which the texture fingerprint does not cover: the scene name tells them apart),
// and so does two_pens (the default bricks under two pens), and two_pens_pinch (a block on them);
// dimpled_ball_grooves lays its ball on grooved_block's grooves.
TEST(SceneSurface, ShippedScenesHaveDistinctFingerprintsUnlessTheirSurfacesAreEqual) {
  std::map<std::uint64_t, std::string> seen;
  std::map<std::string, std::uint64_t> of;
  for (const auto& entry : std::filesystem::directory_iterator(kScenes)) {
    if (entry.path().extension() != ".yaml") continue;
    SurfaceTextureOptions options;
    options.smooth = tex::smoothTexture;
    const SceneSurface s = buildSceneSurface(loadScene(entry.path().string()), options);
    of[s.scene_name] = s.fingerprint;
    // Scenes made on another's surface: the same texture (a mesh scene's hello also hashes the
    // same mesh); their names tell them apart.
    if (s.scene_name == "marble_bricks" || s.scene_name == "marble_bowl" || s.scene_name == "bumpy_marbles_bowl" ||
        s.scene_name == "two_pens" || s.scene_name == "capsule_bricks" || s.scene_name == "two_pens_pinch" ||
        s.scene_name == "dimpled_ball_grooves")
      continue;
    const auto [it, fresh] = seen.emplace(s.fingerprint, s.scene_name);
    EXPECT_TRUE(fresh) << s.scene_name << " and " << it->second << " share " << tex::formatFingerprint(s.fingerprint);
  }
  EXPECT_GE(seen.size(), 8u);
  EXPECT_EQ(of.at("marble_bricks"), of.at("default"));
  EXPECT_EQ(of.at("two_pens"), of.at("default"));
  EXPECT_EQ(of.at("capsule_bricks"), of.at("default"));
  EXPECT_EQ(of.at("two_pens_pinch"), of.at("default"));
  EXPECT_EQ(of.at("marble_bowl"), of.at("brick_bowl"));
  EXPECT_EQ(of.at("bumpy_marbles_bowl"), of.at("brick_bowl"));
  EXPECT_EQ(of.at("dimpled_ball_grooves"), of.at("grooved_block"));
}

}  // namespace

}  // namespace test_scene_surface
