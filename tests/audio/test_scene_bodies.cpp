// What a shipped scene asks the modal analysis for (clients/audio/analysis/scene_bodies.hpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "clients/audio/analysis/scene_bodies.hpp"
#include "scenes/scene_loader.hpp"

namespace thx::audio::test_scene_bodies {
namespace {

std::string scenePath(const std::string& name) { return std::string(THX_SOURCE_DIR) + "/scenes/" + name + ".yaml"; }

TEST(SceneBodies, DefaultSceneIsItsSlabItsMarbleAndThePen) {
  const scene::Scene s = scene::loadScene(scenePath("default"));
  const std::vector<SceneBody> bodies = sceneBodies(s, SceneMeshOptions{});
  ASSERT_EQ(bodies.size(), 3u);
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
  // The pen: device.pen's defaults, a plastic cylinder 12 cm x r 5 mm along z, its tip the centre
  // of its lower end face.
  const SceneBody& pen = bodies[2];
  EXPECT_EQ(pen.mesh.name, "pen");
  EXPECT_EQ(pen.material.name, "plastic");
  lo = pen.mesh.nodes[0], hi = lo;
  for (const Eigen::Vector3d& x : pen.mesh.nodes) lo = lo.cwiseMin(x), hi = hi.cwiseMax(x);
  EXPECT_NEAR(hi.z() - lo.z(), 0.12, 1e-12);
  EXPECT_NEAR(hi.x(), 0.005, 1e-12);
  const Eigen::Vector3d tip = pen.mesh.nodes[std::size_t(penTipNode(pen.mesh))];
  EXPECT_NEAR(tip.z(), -0.06, 1e-12);
  EXPECT_NEAR(tip.head<2>().norm(), 0.0, 1e-12);
}

TEST(SceneBodies, TheSceneSaysTheSlabsThicknessHowItIsHeldAndThePen) {
  const scene::Scene s = scene::parseScene(R"(version: 1
name: held
surface:
  size: [0.1, 0.1]
  texture: {generator: bricks}
  material: steel
  thickness: 0.004
  held: edges
device:
  pen: {radius: 0.003, length: 0.1, material: aluminium}
)",
                                           "held.yaml", "");
  SceneMeshOptions o;
  o.slab_cells = 4;
  const SceneBody slab = slabBody(s, o);
  double low = 0;
  for (const Eigen::Vector3d& x : slab.mesh.nodes) low = std::min(low, x.z());
  EXPECT_NEAR(low, -0.004, 1e-12);
  EXPECT_TRUE(slab.mesh.anyClamped());
  // The command line's overrides win.
  o.slab_thickness_m = 0.01;
  o.clamp_slab = false;
  const SceneBody free = slabBody(s, o);
  low = 0;
  for (const Eigen::Vector3d& x : free.mesh.nodes) low = std::min(low, x.z());
  EXPECT_NEAR(low, -0.01, 1e-12);
  EXPECT_FALSE(free.mesh.anyClamped());
  const SceneBody pen = penBody(s);
  EXPECT_EQ(pen.material.name, "aluminium");
  double r = 0;
  for (const Eigen::Vector3d& x : pen.mesh.nodes) r = std::max(r, x.head<2>().norm());
  EXPECT_NEAR(r, 0.003, 1e-12);
}

TEST(SceneBodies, FixedObstaclesAreSkipped) {
  const scene::Scene s = scene::loadScene(scenePath("letter_blocks"));
  int moving = 0;
  for (const scene::SceneObject& o : s.objects) moving += o.fixed ? 0 : 1;
  ASSERT_LT(moving, int(s.objects.size()));  // the scene has fixed posts
  const std::vector<SceneBody> bodies = sceneBodies(s, SceneMeshOptions{});
  EXPECT_EQ(int(bodies.size()), 1 + moving + 1);  // the slab, the moving objects, the pen
  for (const SceneBody& b : bodies)
    for (const scene::SceneObject& o : s.objects)
      if (o.name == b.mesh.name) {
        EXPECT_FALSE(o.fixed) << o.name;
      }
}

}  // namespace
}  // namespace thx::audio::test_scene_bodies
