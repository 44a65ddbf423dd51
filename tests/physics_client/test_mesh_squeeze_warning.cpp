// A normal map (no depth) on a mesh whose uv squeezes it, with objects on it: physics-client warns
// (MeshGround::warnings), since there the objects read it at one point with its slopes steepened
// as many times (docs/physics.md, Known gaps). A relief, or no objects, gives no warning; the
// squeeze itself is measured against meshes whose uv lays the tile at a known scale.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "clients/physics/mesh_contact.hpp"
#include "clients/physics_client/physics_scene.hpp"
#include "meshes/mesh_generators.hpp"
#include "scenes/scene_loader.hpp"
#include "tests/support/bowl_scene.hpp"

namespace test_mesh_squeeze_warning {

namespace {

using thx::physclient::PhysicsScene;
using thx::physclient::SimOptions;

constexpr const char* kMarble = R"(objects:
  - {name: marble, shape: sphere, radius: 0.006, mass: 0.007, material: steel, position: [0.02, 0.005, -0.012]}
)";

// The shipped bowl of bricks (its floor's centre is a pole of the lathe's uv), read as `representation`.
PhysicsScene bowl(const std::string& representation, const std::string& objects) {
  std::string text = thx::test::bowlOfBricksScene("bowl", 64, 128, objects);
  const std::string relief = "representation: relief";
  text.replace(text.find(relief), relief.size(), "representation: " + representation);
  return PhysicsScene(thx::scene::parseScene(text, "bowl.yaml", "."), SimOptions{});
}

}  // namespace

TEST(MeshSqueezeWarning, ACylinderLaysTheTileAtItsOwnScaleAndATileFourTimesLongerIsSqueezedFourTimes) {
  const thx::mesh::GeneratedMesh tube = thx::mesh::cylinder(0.03, 0.05, 48, 8, 0.01);
  const thx::phys::UvSqueeze own = thx::phys::largestUvSqueeze(tube.mesh, tube.tile_used_m);
  EXPECT_LT(own.factor, 1.01);  // the flat chords are a little shorter than the arcs
  const thx::phys::UvSqueeze four = thx::phys::largestUvSqueeze(tube.mesh, 4.0 * tube.tile_used_m);
  EXPECT_NEAR(four.factor, 4.0, 0.01);
}

TEST(MeshSqueezeWarning, ASpheresUvIsSqueezedAlongUAtItsPoles) {
  const thx::mesh::GeneratedMesh ball = thx::mesh::sphere(0.05, 64, 32, 0.01);
  const thx::phys::UvSqueeze s = thx::phys::largestUvSqueeze(ball.mesh, ball.tile_used_m);
  EXPECT_GT(s.factor, 10.0);
  EXPECT_EQ(s.axis, 0);
  // v runs from pole to pole: the squeeze is within two rings of one (the fan's own triangles
  // have no meaningful scale along u: metresPerUv).
  double v_min = ball.mesh.uvs.front().y(), v_max = v_min;
  for (const Eigen::Vector2d& uv : ball.mesh.uvs) v_min = std::min(v_min, uv.y()), v_max = std::max(v_max, uv.y());
  const double two_rings = 2.0 * (v_max - v_min) / 32.0;
  EXPECT_TRUE(s.uv.y() < v_min + two_rings || s.uv.y() > v_max - two_rings) << "v " << s.uv.y() << " of " << v_min << " to " << v_max;
}

TEST(MeshSqueezeWarning, ANormalMapSqueezedUnderObjectsIsWarnedAboutNamingTheFieldTheAxisAndTheRemedy) {
  const std::vector<std::string> w = bowl("normal", kMarble).warnings();
  ASSERT_EQ(w.size(), 1u);
  EXPECT_NE(w[0].find("surface.mesh"), std::string::npos) << w[0];
  EXPECT_NE(w[0].find("along u"), std::string::npos) << w[0];
  EXPECT_NE(w[0].find("representation: relief"), std::string::npos) << w[0];
}

TEST(MeshSqueezeWarning, AReliefOrASurfaceWithoutObjectsIsNotWarnedAbout) {
  EXPECT_TRUE(bowl("relief", kMarble).warnings().empty());  // a ball meets the relief as its sphere does
  EXPECT_TRUE(bowl("normal", "").warnings().empty());
}

}  // namespace test_mesh_squeeze_warning
