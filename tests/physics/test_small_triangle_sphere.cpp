// A plain ball against a mesh whose triangles are smaller than Bullet's sphere-triangle test sees
// (clients/physics/small_triangle_sphere.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "clients/physics/small_triangle_sphere.hpp"
#include "meshes/mesh_generators.hpp"
#include "tests/physics/textured_ball_on_mesh_scene.hpp"

namespace thx::phys::test::test_small_triangle_sphere {
namespace {

namespace ball = thx::phys::test::textured_ball;

// How many of the mesh's triangles Bullet's own sphere-triangle test would skip as degenerate.
int unseenByBullet(const mesh::TexturedMesh& m) {
  int unseen = 0;
  for (const mesh::Triangle& t : m.triangles) {
    const btVector3 a = toBt(m.positions[t[0]]), b = toBt(m.positions[t[1]]), c = toBt(m.positions[t[2]]);
    unseen += bulletSeesTriangle(a, b, c) ? 0 : 1;
  }
  return unseen;
}

// A plain 1 cm ball pressed by its weight on smooth UV sphere meshes (128 segments) along lines
// through their centres, on and off the world's axes (no gravity, the ball kept from turning,
// 0.2 s): it rests where it touches. On the 5 and 2 mm spheres every triangle is under the
// 0.06 mm^2 Bullet's test skips, and the ball fell through and was thrown out 1.7 m along every
// line; on the 1 cm sphere the pole's fan is, and it fell through along the line to the pole
// (6.6 mm off after 0.6 s; docs/physics.md, "Small triangles").
TEST(SmallTriangleSphere, APlainBallPressedOnASphereMeshOfSmallTrianglesRestsWhereItTouches) {
  const std::vector<Eigen::Vector3d>& lines = ball::kPressLines;
  for (const double sphere_radius : {0.01, 0.005, 0.002}) {
    const double touch = sphere_radius + ball::kRadius;
    // The pole line only on the 1 cm sphere: the others meet triangles Bullet sees.
    for (const Eigen::Vector3d& line : sphere_radius > 0.005 ? std::vector<Eigen::Vector3d>{lines.front()} : lines) {
      const Eigen::Vector3d u = line.normalized();
      mesh_rolling::SphereScene scene(128, true, sphere_radius);
      if (line == lines.front()) {
        const int unseen = unseenByBullet(scene.sphere.mesh);
        std::printf("[measured] %g mm sphere mesh: %d of %zu triangles under Bullet's sphere-triangle floor\n",
                    sphere_radius * 1e3, unseen, scene.sphere.mesh.triangles.size());
        EXPECT_GT(unseen, 0) << sphere_radius;
      }
      Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
      pose.translation() = (touch + 1e-4) * u;
      btRigidBody& b = scene.world.addSphere(ball::kRadius, ball::kMass, pose, {0.5, 0.0, 0.0});
      const ball::PressedRest rest = ball::pressTowardsOrigin(scene.world, b, u, 200);
      std::printf("[measured] plain ball pressed on the %g mm sphere mesh along (%.2f, %.2f, %.2f): at rest %.2f um "
                  "off the touch, %.2f um off the line at most\n",
                  sphere_radius * 1e3, u.x(), u.y(), u.z(), (rest.distance_m - touch) * 1e6, rest.off_line_m * 1e6);
      EXPECT_NEAR(rest.distance_m, touch, 1e-6) << sphere_radius << " m sphere, along " << u.transpose();
      EXPECT_LT(rest.off_line_m, 1e-5) << sphere_radius << " m sphere, along " << u.transpose();
    }
  }
}

// The same ball pressed on a 1 mm rod (a tube mesh of 128 segments and 64 rows over 10 cm: every
// triangle a 0.05 x 1.6 mm sliver under Bullet's floor) towards its axis from five angles round
// it. It fell through along all five before the small triangles were met, and was then thrown off
// along two and rested 0.54 mm in along one until the walk to its foot settled a surface curved
// round it and not along it (SmoothFoot.OnARod...).
TEST(SmallTriangleSphere, APlainBallPressedOnAThinRodMeshRestsWhereItTouches) {
  mesh::GeneratedMesh rod = mesh::cylinder(0.001, 0.1, 128, 64, 0.02);
  EXPECT_EQ(unseenByBullet(rod.mesh), int(rod.mesh.triangles.size()));
  const double touch = 0.001 + ball::kRadius;
  for (const double angle : {0.0, 0.3, 0.7, 1.1, 2.0}) {
    const Eigen::Vector3d u(std::cos(angle), std::sin(angle), 0.0);
    PhysicsWorld world;
    Eigen::Isometry3d rod_pose = Eigen::Isometry3d::Identity();
    rod_pose.translation() = Eigen::Vector3d(0.0, 0.0, -0.05);
    world.addTexturedMesh(rod.mesh, rod_pose, {1.0, 0.0, 0.0}, MeshContactOptions{});
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.translation() = (touch + 1e-4) * u;
    btRigidBody& b = world.addSphere(ball::kRadius, ball::kMass, pose, {0.5, 0.0, 0.0});
    const ball::PressedRest rest = ball::pressTowardsOrigin(world, b, u, 200);
    std::printf("[measured] plain ball pressed on the 1 mm rod mesh at %.1f rad: at rest %.2f um off the touch, %.2f um off "
                "the line at most\n",
                angle, (rest.distance_m - touch) * 1e6, rest.off_line_m * 1e6);
    EXPECT_NEAR(rest.distance_m, touch, 1e-6) << angle << " rad";
    EXPECT_LT(rest.off_line_m, 1e-5) << angle << " rad";
  }
}

}  // namespace
}  // namespace thx::phys::test::test_small_triangle_sphere
