// What a shipped scene asks the modal analysis for (clients/audio/scene_bodies.hpp).
#include <gtest/gtest.h>

#include <string>

#include "clients/audio/scene_bodies.hpp"
#include "scenes/scene_loader.hpp"

namespace thx::audio {
namespace {

std::string scenePath(const std::string& name) { return std::string(THX_SOURCE_DIR) + "/scenes/" + name + ".yaml"; }

TEST(SceneBodies, DefaultSceneIsItsSlabAndItsMarble) {
  const scene::Scene s = scene::loadScene(scenePath("default"));
  const std::vector<SceneBody> bodies = sceneBodies(s, SceneMeshOptions{});
  ASSERT_EQ(bodies.size(), 2u);
  EXPECT_EQ(bodies[0].mesh.name, "surface");
  EXPECT_EQ(bodies[0].material.name, "brick");
  // The slab spans the surface: 0.2 x 0.2 m, 1 cm thick, its top at z = 0.
  Eigen::Vector3d lo = bodies[0].mesh.nodes[0], hi = lo;
  for (const Eigen::Vector3d& x : bodies[0].mesh.nodes) lo = lo.cwiseMin(x), hi = hi.cwiseMax(x);
  EXPECT_NEAR(hi.x() - lo.x(), 0.2, 1e-12);
  EXPECT_NEAR(hi.y() - lo.y(), 0.2, 1e-12);
  EXPECT_NEAR(lo.z(), -0.01, 1e-12);
  EXPECT_NEAR(hi.z(), 0.0, 1e-12);
  EXPECT_EQ(bodies[1].mesh.name, "marble");
  EXPECT_EQ(bodies[1].material.name, "glass");
  for (const Eigen::Vector3d& x : bodies[1].mesh.nodes) EXPECT_LE(x.norm(), 0.008 * (1 + 1e-12));
}

TEST(SceneBodies, FixedObstaclesAreSkipped) {
  const scene::Scene s = scene::loadScene(scenePath("letter_blocks"));
  int moving = 0;
  for (const scene::SceneObject& o : s.objects) moving += o.fixed ? 0 : 1;
  ASSERT_LT(moving, int(s.objects.size()));  // the scene has fixed posts
  const std::vector<SceneBody> bodies = sceneBodies(s, SceneMeshOptions{});
  EXPECT_EQ(int(bodies.size()), 1 + moving);
  for (const SceneBody& b : bodies)
    for (const scene::SceneObject& o : s.objects)
      if (o.name == b.mesh.name) {
        EXPECT_FALSE(o.fixed) << o.name;
      }
}

}  // namespace
}  // namespace thx::audio
