// A ball's bump map shapes its contacts with a relief plane or a mesh (on its chart), not with a
// normal-mapped plane (clients/physics/textured_ball.hpp): physics-client warns when a scene puts
// a ball with a texture on a normal-mapped plane, naming the ball.
#include <gtest/gtest.h>

#include <string>

#include "clients/physics_client/physics_scene.hpp"
#include "scenes/scene_loader.hpp"
#include "tests/support/process.hpp"

namespace test_textured_ball_warning {

namespace {

using thx::physclient::PhysicsScene;

// The shipped dimpled ball scene, its grooves read as `representation`, on a bowl's mesh or not.
PhysicsScene dimpledBall(const std::string& representation, bool bowl = false) {
  std::string text = thx::test::slurp(std::string(THX_SOURCE_DIR) + "/scenes/dimpled_ball_grooves.yaml");
  const std::string relief = "representation: relief", size = "  size: [0.1, 0.1]\n";
  text.replace(text.find(relief), relief.size(), "representation: " + representation);
  if (bowl) text.insert(text.find(size) + size.size(), "  mesh: {generator: bowl, size: 0.06, segments: 32, closed: true}\n");
  return PhysicsScene(thx::scene::parseScene(text, "dimpled_ball_grooves.yaml", "."));
}

}  // namespace

TEST(TexturedBallWarning, ABumpMappedBallOnANormalMappedPlaneIsWarnedAboutByName) {
  EXPECT_TRUE(dimpledBall("relief").warnings().empty());
  const std::vector<std::string> warnings = dimpledBall("normal").warnings();
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("ball 'ball': its bump map shapes its contacts with a relief plane or a mesh only; on "
                             "this scene's normal-mapped plane it collides as the plain ball"),
            std::string::npos)
      << warnings[0];
  // On a mesh, relief or normal map (met as the relief its normals integrate to), it is read.
  EXPECT_TRUE(dimpledBall("relief", true).warnings().empty());
  EXPECT_TRUE(dimpledBall("normal", true).warnings().empty());
}

}  // namespace test_textured_ball_warning
