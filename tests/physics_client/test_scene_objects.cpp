// The scene format's objects: fixed obstacles and angular velocity (backward-compatible additions),
// with errors naming file:line, field and value.
#include <gtest/gtest.h>

#include "scenes/scene_loader.hpp"

namespace test_scene_objects {

namespace {

using namespace thx::scene;

const std::string kHead = R"(version: 1
name: t
surface:
  size: [0.2, 0.2]
  texture: {generator: sine, size: 32}
objects:
)";

Scene parse(const std::string& objects) { return parseScene(kHead + objects, "t.yaml", "."); }

std::string errorOf(const std::string& objects) {
  try {
    parse(objects);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(SceneObjects, OldObjectsStillReadTheSame) {
  const Scene s = parse("  - {name: b, shape: sphere, radius: 0.01, mass: 0.01, position: [0, 0, 0.01]}\n");
  ASSERT_EQ(s.objects.size(), 1u);
  EXPECT_FALSE(s.objects[0].fixed);
  EXPECT_EQ(s.objects[0].angular_velocity_rad_per_s, Eigen::Vector3d::Zero());
  EXPECT_DOUBLE_EQ(s.objects[0].mass_kg, 0.01);
}

TEST(SceneObjects, FixedObstacleNeedsNoMass) {
  const Scene s = parse(
      "  - {name: post, shape: cylinder, radius: 0.005, length: 0.02, fixed: true, position: [0, 0, 0.01]}\n"
      "  - {name: b, shape: box, size: [0.01, 0.01, 0.01], mass: 0.01, position: [0.05, 0, 0.005],\n"
      "     angular_velocity: [0, 0, 3]}\n");
  ASSERT_EQ(s.objects.size(), 2u);
  EXPECT_TRUE(s.objects[0].fixed);
  EXPECT_EQ(s.objects[0].mass_kg, 0.0);
  EXPECT_FALSE(s.objects[1].fixed);
  EXPECT_EQ(s.objects[1].angular_velocity_rad_per_s, Eigen::Vector3d(0, 0, 3));
}

TEST(SceneObjects, ErrorsNameLineFieldAndValue) {
  std::string m = errorOf("  - {name: p, shape: sphere, radius: 0.01, fixed: true, mass: 1, position: [0, 0, 0]}\n");
  EXPECT_NE(m.find("t.yaml:7:"), std::string::npos) << m;
  EXPECT_NE(m.find("objects[0].mass"), std::string::npos) << m;
  EXPECT_NE(m.find("does not apply to a fixed object"), std::string::npos) << m;

  m = errorOf("  - {name: p, shape: sphere, radius: 0.01, fixed: yes, position: [0, 0, 0]}\n");
  EXPECT_NE(m.find("objects[0].fixed"), std::string::npos) << m;
  EXPECT_NE(m.find("'yes'"), std::string::npos) << m;

  m = errorOf("  - {name: p, shape: sphere, radius: 0.01, position: [0, 0, 0]}\n");
  EXPECT_NE(m.find("objects[0].mass"), std::string::npos) << m;
  EXPECT_NE(m.find("fixed: true"), std::string::npos) << m;

  m = errorOf("  - {name: p, shape: sphere, radius: 0.01, mass: 1, position: [0, 0, 0], angular_velocity: [0, .nan, 0]}\n");
  EXPECT_NE(m.find("objects[0].angular_velocity[1]"), std::string::npos) << m;

  m = errorOf("  - {name: p, shape: sphere, radius: 0.01, mass: 1, position: [0, 0, 0], angular_velocty: [0, 0, 0]}\n");
  EXPECT_NE(m.find("did you mean 'angular_velocity'"), std::string::npos) << m;

  m = errorOf("  - {name: p, shape: sphere, radius: 0.01, fixed: true, velocity: [1, 0, 0], position: [0, 0, 0]}\n");
  EXPECT_NE(m.find("objects[0].velocity"), std::string::npos) << m;
}

}  // namespace

}  // namespace test_scene_objects
