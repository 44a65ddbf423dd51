// The staged scene folder of a real session (docs/study.md §7): every scene of the manifest and
// Study 1's variants load; NAME.nopen renders no force on the servo rig, NAME.noball has no
// objects, NAME.nosound has audio.mute, and none changes the surface.
#include <gtest/gtest.h>

#include <filesystem>

#include "clients/study/scene_stage.hpp"
#include "clients/study/surface_percept.hpp"
#include "scenes/scene_loader.hpp"
#include "scenes/scene_surface.hpp"
#include "tests/support/temp_dir.hpp"

namespace thx::study::test_scene_stage {
namespace {

const std::string kData = THX_TEST_DATA_DIR "/study";

TEST(SceneStage, VariantsRemoveThePenForceTheBallOrTheSoundOnly) {
  test::TempDir dir("study_stage");
  const StudyManifest m = loadManifest(kData + "/identification/manifest.yaml");
  const auto files = stageScenes(m, dir.path().string());
  EXPECT_EQ(files.size(), 1 + 4 * m.surfaces.size());
  for (const auto& f : files) EXPECT_NO_THROW(scene::loadScene(f)) << f;

  const std::string orig = m.surfaces[0].scene;
  EXPECT_EQ(stagedSceneName(orig, Cues{}), "bricks_large");
  EXPECT_EQ(stagedSceneName(orig, Cues{true, true, false}), "bricks_large.nopen");
  EXPECT_EQ(stagedSceneName(orig, Cues{true, false, true}), "bricks_large.noball");
  EXPECT_EQ(stagedSceneName(orig, Cues{false, true, true}), "bricks_large.nosound");

  const scene::Scene a = scene::loadScene(orig);
  const scene::Scene same = scene::loadScene(dir.file("bricks_large.yaml"));
  const scene::Scene no_pen = scene::loadScene(dir.file("bricks_large.nopen.yaml"));
  const scene::Scene no_ball = scene::loadScene(dir.file("bricks_large.noball.yaml"));
  const scene::Scene no_sound = scene::loadScene(dir.file("bricks_large.nosound.yaml"));
  const auto print = [](const scene::Scene& s) { return scene::buildSceneSurface(s).fingerprint; };
  EXPECT_EQ(print(same), print(a));
  EXPECT_EQ(print(no_pen), print(a));
  EXPECT_EQ(print(no_ball), print(a));
  EXPECT_EQ(print(no_sound), print(a));
  EXPECT_FALSE(a.audio.mute);
  EXPECT_FALSE(no_pen.audio.mute);
  EXPECT_FALSE(no_ball.audio.mute);
  EXPECT_TRUE(no_sound.audio.mute);  // the audio client plays silence; nothing else changes:
  EXPECT_EQ(no_sound.objects.size(), a.objects.size());
  EXPECT_EQ(no_sound.device.stiffness_fraction, a.device.stiffness_fraction);
  EXPECT_EQ(no_sound.device.damping_ns_per_m, a.device.damping_ns_per_m);
  EXPECT_EQ(a.objects.size(), 1u);
  EXPECT_EQ(no_pen.objects.size(), 1u);
  EXPECT_TRUE(no_ball.objects.empty());
  EXPECT_EQ(no_pen.device.stiffness_fraction, 0.0);
  EXPECT_EQ(no_ball.device.stiffness_fraction, a.device.stiffness_fraction);

  // Rendered as hapticd prepares it: the variant with every cue "on" gives no pen force at all.
  const Percept p = measureSurface(dir.file("bricks_large.nopen.yaml"), Cues{});
  EXPECT_FALSE(p.features[kPenLateral]);
  EXPECT_EQ(p.features[kBallShake], measureSurface(orig, Cues{}).features[kBallShake]);
}

TEST(SceneStage, ReliefVsNormalStagesBothVersionsWithoutVariants) {
  test::TempDir dir("study_stage");
  const StudyManifest m = loadManifest(kData + "/relief_vs_normal/manifest.yaml");
  const auto files = stageScenes(m, dir.path().string());
  EXPECT_EQ(files.size(), 2 * m.surfaces.size());
  EXPECT_TRUE(std::filesystem::exists(dir.file("wood_relief.yaml")));
  EXPECT_TRUE(std::filesystem::exists(dir.file("wood_normal.yaml")));
  EXPECT_FALSE(std::filesystem::exists(dir.file("wood_normal.nopen.yaml")));
  EXPECT_FALSE(std::filesystem::exists(dir.file("wood_normal.nosound.yaml")));
}

}  // namespace
}  // namespace thx::study::test_scene_stage
