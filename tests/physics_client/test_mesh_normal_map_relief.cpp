// A normal map (no depth) on a mesh is met by every body as the relief its normals integrate to
// (MeshGround), so bumps the mesh's uv squeezes (a lathe's or a UV sphere's pole) are met as a
// relief, not sampled at one point; a map that leans on average leans its contacts' normals by
// its mean slope (docs/physics.md, "Mesh scenes in physics-client"). No such scene is warned about.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "clients/physics/mesh_contact.hpp"
#include "clients/physics_client/physics_scene.hpp"
#include "scenes/scene_loader.hpp"
#include "tests/support/bowl_scene.hpp"
#include "tests/support/sanitized_build.hpp"

namespace test_mesh_normal_map_relief {

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

// The same bowl with a uniformly tilted normal map (5 degrees): its slopes lean on average.
PhysicsScene tiltedBowl(const std::string& objects) {
  std::string text = thx::test::bowlOfBricksScene("bowl", 64, 128, objects);
  const std::size_t from = text.find("    generator: bricks"), to = text.find("  representation: relief");
  text.replace(from, to - from, "    generator: tilted\n    size: 64\n    params: {angle_deg: 5}\n");
  const std::string relief = "representation: relief";
  text.replace(text.find(relief), relief.size(), "representation: normal");
  return PhysicsScene(thx::scene::parseScene(text, "bowl.yaml", "."), SimOptions{});
}

}  // namespace

TEST(MeshNormalMapRelief, NoSurfaceOrObjectsOnAMeshAreWarnedAbout) {
  EXPECT_TRUE(bowl("relief", kMarbleAndBlock).warnings().empty());
  EXPECT_TRUE(bowl("normal", kMarbleAndBlock).warnings().empty());
  // A leaning map squeezed under a block (until 2026-12-03 the block read it at one point, and
  // physics-client warned).
  EXPECT_TRUE(tiltedBowl(kMarbleAndBlock).warnings().empty());
  EXPECT_TRUE(tiltedBowl("").warnings().empty());
}

// What a ball meets instead: the relief the normal map's normals integrate to (MeshGround), the
// bricks level on average; a relief map's own relief.
TEST(MeshNormalMapRelief, EveryBodyIsGivenTheReliefALevelNormalMapsNormalsIntegrateTo) {
  const PhysicsScene normal = bowl("normal", kMarble), relief = bowl("relief", kMarble);
  const thx::phys::MeshContactOptions& n = normal.meshGround()->contactOptions();
  ASSERT_NE(n.ball_relief, nullptr);
  EXPECT_GT(n.texture->maxDepth(), 0.0);  // boxes and rods meet it on its chart
  EXPECT_EQ(n.relief_mean_slope, Eigen::Vector2d::Zero());
  const thx::phys::MeshContactOptions& r = relief.meshGround()->contactOptions();
  ASSERT_NE(r.ball_relief, nullptr);
  EXPECT_GT(r.texture->maxDepth(), 0.0);
  EXPECT_EQ(r.relief_mean_slope, Eigen::Vector2d::Zero());
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

// A map that leans on average cannot be a periodic relief: every body meets the relief (flat for
// a uniformly tilted map), its contacts' normals leaning by the mean slope.
TEST(MeshNormalMapRelief, ALeaningNormalMapIsMetAsItsReliefLeaningByItsMeanSlope) {
  const PhysicsScene tilted = tiltedBowl(kMarbleAndBlock);
  const thx::phys::MeshContactOptions& o = tilted.meshGround()->contactOptions();
  ASSERT_NE(o.ball_relief, nullptr);
  EXPECT_TRUE(o.texture->isRelief());
  EXPECT_NEAR(o.relief_mean_slope.norm(), std::tan(5.0 * M_PI / 180.0), 1e-3);
}

// The bowl of bricks as a normal map with a block on its floor, around the pole of the lathe's uv
// that squeezes it: met as the bricks' integrated relief, the block comes to rest at both places,
// where read at one point it kept rocking at 1.76 and 1.86 mm/s (2026-12-03, the code before;
// on the 128-segment bowl, 21 places around the pole: 10 at rest read at one point, all 21 on the
// integrated relief and on the bricks' own relief map since 2026-12-05, bench_block_by_pole).
TEST(MeshNormalMapRelief, ABlockOnALevelNormalMapSqueezedAtTheBowlsFloorComesToRest) {
  for (const Eigen::Vector2d& at : {Eigen::Vector2d(-0.0023, 0.0067), Eigen::Vector2d(0.0132, 0.0042)}) {
    // The floor's height under the block's centre: half an ellipsoid, 55.2 mm across and 43.2 mm
    // deep, its lowest point 35.2 mm below the world's origin (tests/support/bowl_scene.hpp).
    const double z = -0.0352 + 0.0432 * (1.0 - std::sqrt(1.0 - at.squaredNorm() / (0.0552 * 0.0552))) + 0.0035;
    char objects[300];
    std::snprintf(objects, sizeof objects,
                  "objects:\n  - {name: block, shape: box, size: [0.01, 0.01, 0.006], mass: 0.005, material: wood, "
                  "position: [%.4f, %.4f, %.4f], rpy_deg: [0, 0, 20]}\n", at.x(), at.y(), z);
    PhysicsScene scene = bowl("normal", objects);
    double peak = 0.0;
    for (int k = 1; k <= 3000; ++k) {
      scene.step(1e-3);
      if (k > 2000) peak = std::max(peak, scene.body(0).v_world.norm());
    }
    std::printf("[measured] block at (%.1f, %.1f) mm from the floor's centre: peak speed 2-3 s %.4f mm/s\n", at.x() * 1e3,
                at.y() * 1e3, peak * 1e3);
    EXPECT_LT(peak, 1e-4) << at.transpose();
  }
}

}  // namespace test_mesh_normal_map_relief

namespace test_mesh_normal_map_relief {

// The shipped bowl of bricks (128 segments) as its normal map (met as the relief its normals
// integrate to) and as its relief map, a block set down around the pole of the lathe's uv at
// bench_block_by_pole's places 2 and 10 mm from a point 0.76 mm off it, turned three ways: it
// comes to rest at every one. There the chart under the block reads the bricks squeezed 5 to 31
// times along u; read at a stride, which texels it read moved with the block, and at its foot's
// triangle's own scale, which halves across alternate edges by the pole, the laid texture jumped
// (2026-12-05, the code before, with the chart smooth on the pole's fan as now: 3.96 and
// 5.94 mm/s on the normal map's relief). The chart now reads the relief's envelope merged along u
// (relief_envelope.hpp) at the scale interpolated from the vertices (mesh_relief_chart.cpp).
TEST(MeshNormalMapRelief, ABlockAroundTheSqueezedPoleOfTheBowlComesToRestReadEitherWay) {
  // The sanitizer build: the normal map, turned the one way that rocked (39 s for all twelve).
  const std::vector<const char*> representations =
      thx::test::kSanitized ? std::vector<const char*>{"normal"} : std::vector<const char*>{"normal", "relief"};
  const std::vector<double> turns = thx::test::kSanitized ? std::vector<double>{1.9} : std::vector<double>{0.3, 1.9, 3.6};
  for (const char* representation : representations) {
    double worst = 0.0;
    for (double r : {2.0, 10.0})
      for (double turn : turns) {
        const Eigen::Vector2d at(0.0007 + 1e-3 * r * std::cos(turn), 0.0003 + 1e-3 * r * std::sin(turn));
        const double floor_z = -0.0352 + 0.0432 * (1.0 - std::sqrt(1.0 - at.squaredNorm() / (0.0552 * 0.0552)));
        char objects[320];
        std::snprintf(objects, sizeof objects,
                      "objects:\n  - {name: block, shape: box, size: [0.01, 0.01, 0.006], mass: 0.005, material: wood, "
                      "position: [%.5f, %.5f, %.5f], rpy_deg: [0, 0, %.1f]}\n",
                      at.x(), at.y(), floor_z + 0.0035, turn * 180.0 / M_PI);
        std::string text = thx::test::bowlOfBricksScene("bowl", 128, 128, objects);
        const std::string relief = "representation: relief";
        text.replace(text.find(relief), relief.size(), std::string("representation: ") + representation);
        PhysicsScene scene(thx::scene::parseScene(text, "bowl.yaml", "."), SimOptions{});
        double peak = 0.0;
        for (int k = 1; k <= 3000; ++k) {
          scene.step(1e-3);
          if (k > 2000) peak = std::max(peak, scene.body(0).v_world.norm());
        }
        worst = std::max(worst, peak);
        EXPECT_LT(peak, 1e-4) << representation << " r " << r << " mm, turned " << turn;
      }
    std::printf("[measured] block around the bowl's pole (%s), %zu places 2 and 10 mm out: fastest 2-3 s %.4f mm/s\n",
                representation, 2 * turns.size(), worst * 1e3);
  }
}

}  // namespace test_mesh_normal_map_relief
