// A normal map (no depth) on a mesh whose uv squeezes it, with boxes, capsules or cylinders on it:
// physics-client warns (MeshGround::warnings), since there they read it at one point with its
// slopes steepened as many times (docs/physics.md, Known gaps). A relief, balls alone (they meet
// the relief the map's normals integrate to) or no objects give no warning; the squeeze itself is
// measured against meshes whose uv lays the tile at a known scale.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
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
constexpr const char* kMarbleAndBlock = R"(objects:
  - {name: marble, shape: sphere, radius: 0.006, mass: 0.007, material: steel, position: [0.02, 0.005, -0.012]}
  - {name: block, shape: box, size: [0.01, 0.01, 0.01], mass: 0.008, material: wood, position: [-0.02, 0.0, -0.01]}
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

TEST(MeshSqueezeWarning, ANormalMapSqueezedUnderABoxIsWarnedAboutNamingTheFieldTheAxisAndTheRemedy) {
  const std::vector<std::string> w = bowl("normal", kMarbleAndBlock).warnings();
  ASSERT_EQ(w.size(), 1u);
  EXPECT_NE(w[0].find("surface.mesh"), std::string::npos) << w[0];
  EXPECT_NE(w[0].find("along u"), std::string::npos) << w[0];
  EXPECT_NE(w[0].find("representation: relief"), std::string::npos) << w[0];
}

TEST(MeshSqueezeWarning, AReliefBallsAloneOrASurfaceWithoutObjectsAreNotWarnedAbout) {
  EXPECT_TRUE(bowl("relief", kMarbleAndBlock).warnings().empty());  // every shape meets a relief as a relief
  EXPECT_TRUE(bowl("normal", kMarble).warnings().empty());  // a ball meets the relief the normals integrate to
  EXPECT_TRUE(bowl("normal", "").warnings().empty());
}

// What a ball meets instead: the relief the normal map's normals integrate to (MeshGround), the
// bricks level on average; a relief map's own relief.
TEST(MeshSqueezeWarning, ABallIsGivenTheReliefANormalMapsNormalsIntegrateTo) {
  const PhysicsScene normal = bowl("normal", kMarble), relief = bowl("relief", kMarble);
  const thx::phys::MeshContactOptions& n = normal.meshGround()->contactOptions();
  ASSERT_NE(n.ball_relief, nullptr);
  EXPECT_EQ(n.texture->maxDepth(), 0.0);  // boxes and rods still read the normal map itself
  EXPECT_LT(n.ball_relief_mean_slope.norm(), 1e-3);
  const thx::phys::MeshContactOptions& r = relief.meshGround()->contactOptions();
  ASSERT_NE(r.ball_relief, nullptr);
  EXPECT_GT(r.texture->maxDepth(), 0.0);
  EXPECT_EQ(r.ball_relief_mean_slope, Eigen::Vector2d::Zero());
  // A 6 mm ball over the same place of a brick is held at the same scale by either: the integrated
  // relief is the relief map's own as far as its normals agree with its depth, which a generator's
  // do away from creases (test_generators.cpp) and not across a brick's edge, where the least-
  // squares fit spreads the difference (measured -297 against -96 um below each relief's top).
  const thx::tex::TexCoord uv{0.37, 0.41};
  const Eigen::Vector2d metres_per_uv = normal.meshGround()->contactOptions().normals_made_for_m;
  const double lift_normal = n.ball_relief->touch(uv, metres_per_uv, 0.006).lift_m;
  const double lift_relief = r.ball_relief->touch(uv, metres_per_uv, 0.006).lift_m;
  std::printf("[measured] a 6 mm ball over the bricks at uv (0.37, 0.41): lifted %.1f um on the normal map's relief, "
              "%.1f um on the relief map (its depth %.1f um)\n", lift_normal * 1e6, lift_relief * 1e6, r.texture->maxDepth() * 1e6);
  EXPECT_LT(std::fabs(lift_normal - lift_relief), r.texture->maxDepth());
}

}  // namespace test_mesh_squeeze_warning
