// A ball with a bump map on a mesh (issue 29; clients/physics/textured_ball.hpp,
// mesh_relief_chart.hpp): it meets the mesh on the chart under it, both reliefs in the contact,
// as it meets the relief plane. Its recessed surface rolls: a ball recessed by d everywhere swings
// in a smooth bowl and leaves the top of a smooth sphere as a rigid ball of radius rho = r - d
// whose inertia is the whole ball's (2/5 m r^2), and a bumpy ball rests on a flat relief mesh as
// on the relief plane. A plain ball keeps Bullet's points, lifted (mesh_contact.hpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <vector>

#include "clients/physics/relief_collision.hpp"
#include "tests/physics/textured_ball_on_mesh_scene.hpp"
#include "tests/support/sanitized_build.hpp"

namespace thx::phys::test::test_textured_ball_on_mesh {
namespace {

namespace ball = textured_ball;
using namespace textured_ball_on_mesh;

TEST(TexturedBallOnMesh, TheChartTakesABallWithABumpMapAndNotAPlainBall) {
  const tex::TextureMap map = ball::bumpMap(3e-4);
  const FaceTexture texture = ball::ballTexture(map);
  mesh_rolling::SphereScene scene(32, true, 0.05);
  btRigidBody& bumpy = scene.world.addTexturedSphere(ball::kRadius, ball::kMass, mesh_rolling::placedAt({0, 0, 0.2}),
                                                     {1.0, 0.0, 0.0}, texture);
  btRigidBody& plain =
      scene.world.addSphere(ball::kRadius, ball::kMass, mesh_rolling::placedAt({0, 0, 0.3}), {1.0, 0.0, 0.0});
  const btCollisionShape& sphere_mesh = *scene.world.world().getCollisionObjectArray()[0]->getCollisionShape();
  ASSERT_NE(meshReliefOf(sphere_mesh), nullptr);
  EXPECT_TRUE(reliefTakesMeshPair(*bumpy.getCollisionShape(), sphere_mesh));
  EXPECT_FALSE(reliefTakesMeshPair(*plain.getCollisionShape(), sphere_mesh));
}

TEST(TexturedBallOnMesh, ARecessedBallSwingsInASmoothBowlOnItsRecessedRadius) {
  // Measured -0.31 % over three periods at 128 segments, and over two (-0.93 % at 64); the plain
  // ball's answer is 9.4 % shorter. Under the sanitizers two periods instead of three (each step
  // of the ball costs about a millisecond optimised).
  const double expected = recessedSwingAnswer(0.05, 5.0);
  const double period = recessedSwing(0.05, 5.0, thx::test::kSanitized ? 1.2 : 2.2).value;
  EXPECT_NEAR(period / expected - 1.0, 0.0, 0.01) << period << " s against " << expected << " s";
}

TEST(TexturedBallOnMesh, ARecessedBallLeavesASphereWhereItsRecessedRadiusSays) {
  // 56.66 degrees from 5 degrees, where a plain ball leaves at 54.13 (10/17 cos(theta0)).
  // Measured 56.61 on the smooth chart and on a flat relief of 0.16 mm texels (56.74 at 39 µm).
  const double expected = recessedDepartureAnswer(5.0);
  const tex::TextureMap flat = flatRelief(64);
  // Under the sanitizers on the relief's chart only (the smooth chart's path is the swing's).
  if (!thx::test::kSanitized) {
    EXPECT_NEAR(recessedDeparture(0.1, 5.0, nullptr).value, expected, 0.3);
  }
  EXPECT_NEAR(recessedDeparture(0.1, 5.0, &flat).value, expected, 0.3);
}

// A recessed ball pressed on a smooth UV sphere mesh (a scene's surface) by its weight along lines
// through the sphere's centre, on and off the world's axes (no gravity, the ball kept from
// turning, 0.6 s): it rests where its recessed sphere touches the smooth one, on a 2 cm sphere, on
// one of the ball's own 1 cm radius, and on ones of 5, 1 and 0.25 mm (others: SmoothFoot.*,
// ChartBoundary.*, and by hand 7.5, 3, 2, 1.5 and 0.5 mm alike: docs/physics.md). On the 1 cm sphere the faces
// far round it that the ball's reach box holds at its corners were taken for creases before
// 2026-12-05, late evening, and the ball rested 173-640 um off its touch along three lines off
// the axes (chart_boundary.hpp). On the smaller ones the walk to the foot of its centre swung
// round the sphere ever wider (smoothFoot) until 2026-12-06: 108 and 130 um off along two lines
// on the 5 mm sphere, thrown off along one on the 2 mm sphere and 13-28 um off along two more. On
// the 1 mm sphere, faces 60 degrees round from the foot were taken for surfaces across a crease
// until 2026-12-06, later, and the ball was thrown off along all five lines; on the 0.25 mm sphere
// it was thrown off along one line more until the damped walk read h / R from the sphere's bend.
TEST(TexturedBallOnMesh, PressedOnASmoothSphereMeshAlongAnyLineItRestsWhereItTouches) {
  const tex::TextureMap recess_map = ball::uniformRecess(0.5e-3);
  const FaceTexture recessed = ball::ballTexture(recess_map);
  const std::vector<Eigen::Vector3d>& lines = ball::kPressLines;
  for (const double sphere_radius : {0.02, 0.01, 0.005, 0.001, 0.00025}) {
    const double touch = sphere_radius + ball::kRadius - 0.5e-3;
    // On the 0.25 mm sphere the whole mesh lies within the ball's reach, and a step costs
    // 0.3-0.5 ms: the line it was thrown along only.
    for (const Eigen::Vector3d& line : sphere_radius < 0.001 ? std::vector<Eigen::Vector3d>{lines.back()} : lines) {
      const Eigen::Vector3d u = line.normalized();
      mesh_rolling::SphereScene scene(128, true, sphere_radius);
      Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
      pose.translation() = (touch + 1e-4) * u;
      btRigidBody& b = scene.world.addTexturedSphere(ball::kRadius, ball::kMass, pose, {0.5, 0.0, 0.0}, recessed);
      const ball::PressedRest rest = ball::pressTowardsOrigin(scene.world, b, u);
      std::printf("[measured] recessed ball pressed on the %g cm sphere mesh along (%.2f, %.2f, %.2f): at rest %.2f um "
                  "off the touch, %.2f um off the line at most\n",
                  sphere_radius * 100, u.x(), u.y(), u.z(), (rest.distance_m - touch) * 1e6, rest.off_line_m * 1e6);
      EXPECT_NEAR(rest.distance_m, touch, 1e-6) << sphere_radius << " m sphere, along " << u.transpose();
      EXPECT_LT(rest.off_line_m, 1e-6) << sphere_radius << " m sphere, along " << u.transpose();
    }
  }
}

TEST(TexturedBallOnMesh, ABumpyBallRestsOnAFlatReliefMeshAsOnTheReliefPlane) {
  const tex::TextureMap flat = flatRelief(256);
  const ball::Settled on_mesh = settleOnSlab(flat, 2.5);
  const ball::Settled on_plane = ball::settleBumpyBall(flat, 2.5);
  // Measured: at one height to the bit, both at rest: on either flat relief it meets the ground by
  // its own lowest points (ball_on_flat_ground.hpp; 4 nm apart when each read its ground's texels,
  // the mesh's chart being the plane's texels laid on its face).
  EXPECT_NEAR(on_mesh.height, on_plane.height, 1e-7) << on_mesh.centre.transpose() << " against " << on_plane.centre.transpose();
  EXPECT_LT(on_mesh.fastest, 1e-4);
}

}  // namespace
}  // namespace thx::phys::test::test_textured_ball_on_mesh
