// A ball on a relief plane whose texels are coarse against its radius can jitter on the texel
// centres its contacts stand on where the relief has features at its texels (docs/physics.md,
// Known gaps): physics-client warns when it loads such a scene, naming the ball and the texels
// that would do (coarseReliefWarning).
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "clients/physics_client/physics_scene.hpp"
#include "scenes/scene_loader.hpp"
#include "tests/support/process.hpp"

namespace test_coarse_relief_warning {

namespace {

using thx::physclient::coarseReliefWarning;
using thx::physclient::PhysicsScene;

// The shipped dimple_ball scene (a 5 mm ball, 0.2 m of relief, 512 texels a side) with `texels`
// a side, read as `representation`.
PhysicsScene dimpleBall(int texels, const std::string& representation = "relief") {
  std::string text = thx::test::slurp(std::string(THX_SOURCE_DIR) + "/scenes/dimple_ball.yaml");
  const std::string size = "size: 512", relief = "representation: relief";
  text.replace(text.find(size), size.size(), "size: " + std::to_string(texels));
  text.replace(text.find(relief), relief.size(), "representation: " + representation);
  return PhysicsScene(thx::scene::parseScene(text, "dimple_ball.yaml", "."));
}

}  // namespace

TEST(CoarseReliefWarning, ABallIsWarnedAboutTexelsOverAQuarterOfItsRadius) {
  const Eigen::Vector2d surface(0.5, 0.5);
  // The shipped scenes' finest ball on their texels (zigzag_street: 4 mm, 0.39 mm texels): quiet.
  EXPECT_EQ(coarseReliefWarning("ball1", 0.004, Eigen::Vector2d::Constant(0.2 / 512), surface), "");
  EXPECT_EQ(coarseReliefWarning("b", 0.004, Eigen::Vector2d::Constant(0.001), surface), "");  // exactly a quarter
  // 3.91 mm texels under a 5 mm ball.
  const std::string coarse = coarseReliefWarning("marble", 0.005, Eigen::Vector2d::Constant(0.5 / 128), surface);
  EXPECT_NE(coarse.find("ball 'marble' (radius 5.00 mm) on relief texels of 3.91 mm"), std::string::npos) << coarse;
  EXPECT_NE(coarse.find("texels of 1.25 mm or less would do (400 x 400 over the 0.500 x 0.500 m surface)"),
            std::string::npos)
      << coarse;
  // The coarser axis counts.
  EXPECT_NE(coarseReliefWarning("b", 0.004, {0.0005, 0.002}, surface), "");
}

TEST(CoarseReliefWarning, PhysicsClientWarnsAboutABallOnACoarseReliefPlaneOnly) {
  EXPECT_TRUE(dimpleBall(512).warnings().empty());  // as shipped: 0.39 mm texels under a 5 mm ball
  const std::vector<std::string> coarse = dimpleBall(100).warnings();  // 2 mm texels
  ASSERT_EQ(coarse.size(), 1u);
  EXPECT_NE(coarse[0].find("ball 'ball' (radius 5.00 mm) on relief texels of 2.00 mm"), std::string::npos) << coarse[0];
  // The same texture as a normal map: the ball meets the flat plane.
  EXPECT_TRUE(dimpleBall(100, "normal").warnings().empty());
}

TEST(CoarseReliefWarning, NoShippedSceneIsWarnedAbout) {
  int scenes = 0;
  for (const auto& entry : std::filesystem::directory_iterator(std::string(THX_SOURCE_DIR) + "/scenes")) {
    if (entry.path().extension() != ".yaml") continue;
    const PhysicsScene scene(thx::scene::loadScene(entry.path().string()));
    const std::vector<std::string> warnings = scene.warnings();
    EXPECT_TRUE(warnings.empty()) << entry.path() << ": " << (warnings.empty() ? "" : warnings[0]);
    ++scenes;
  }
  EXPECT_GE(scenes, 18);
}

}  // namespace test_coarse_relief_warning
