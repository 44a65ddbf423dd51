// Scene files: the fuzz body's seeds and short run (scene_body.hpp), and the size cap on scene text.
#include <gtest/gtest.h>

#include "tests/fuzz/short_run.hpp"
#include "tests/fuzz/scene_body.hpp"

namespace test_fuzz_scene {

using namespace thx;
using namespace thx::fuzz;

namespace {
const std::string kTarget = "scene";
}

TEST(FuzzScene, SeedsHoldTheProperties) { expectSeedsHold(kTarget, &fuzzSceneOnce); }

TEST(FuzzScene, CorpusScenesAreAccepted) {
  // Guards the corpus's value: every seed is a valid scene (the shipped ones at a small texture
  // size, and two naming the fixture's texture and path files), so mutations start deep.
  for (const Bytes& seed : loadCorpus(kTarget)) {
    const std::string text(seed.begin(), seed.end());
    EXPECT_NO_THROW(scene::parseScene(text, kSceneSource, scene_detail::sceneDir().string())) << text;
  }
}

TEST(FuzzScene, ShortRun) { shortRun(kTarget, &fuzzSceneOnce, 300); }

TEST(FuzzScene, RefusesTextAboveTheSceneCap) {
  const std::string text = "name: big\n# " + std::string(1 << 20, 'x') + "\n";
  try {
    scene::parseScene(text, "big.yaml", "");
    FAIL() << "accepted";
  } catch (const scene::SceneError& e) {
    EXPECT_EQ(e.where().file, "big.yaml");
    EXPECT_EQ(e.problem(), "text too large for a scene");
    EXPECT_EQ(e.value(), std::to_string(text.size()) + " bytes");
  }
}

}  // namespace test_fuzz_scene
