// A plain ball against a textured box (ball_on_object_faces.hpp): the box's faces met as the same
// relief laid on a box mesh is met (mesh_contact.hpp, the ball lifted). The grooves of
// grooved_block_scene.hpp (V-grooves along y, 4 mm apart, 1 mm deep) on the faces of a
// 0.2 x 0.2 x 0.02 m box and on the top of the slab mesh of that size; a 5 mm, 4 g ball let down
// in a groove. Before, the ball met the coarse box and rested on the ridges' top (0.41 mm higher).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "tests/physics/grooved_block_scene.hpp"
#include "textures/ball_on_relief.hpp"

namespace thx::phys::test::test_ball_on_box_faces {
namespace {

using namespace grooved_block;

constexpr double kRadius = 0.005, kBallMass = 0.004;
const Eigen::Vector3d kSlabHalf(0.1, 0.1, 0.01);

FaceTexture facesOf(const tex::TextureMap& map) {
  FaceTexture faces;
  faces.map = &map;
  faces.tile_m = kExtent;  // on the top face u runs along x from its centre, as on the slab mesh
  return faces;
}

// The ball let down in a groove (x = P / 2) at y = 13 mm, on the fixed textured box or on the
// grooved slab mesh: its centre after `seconds`.
Eigen::Vector3d letDown(bool box, double seconds) {
  const tex::TextureMap map = heightMap(128, kExtent, vGrooves);
  const tex::BallOnRelief ball_relief(map, tex::Address::Wrap);
  const mesh::GeneratedMesh slab = groovedGround(false);
  PhysicsWorld world;
  if (box) {
    world.addTexturedBox(kSlabHalf, 0.0, at(0.0, 0.0, -0.01), {1.0, 0.0, 0.0}, facesOf(map));
  } else {
    MeshContactOptions options;
    options.texture = &map;
    options.normals_made_for_m = Eigen::Vector2d::Constant(kExtent);
    options.ball_relief = &ball_relief;
    world.addTexturedMesh(slab.mesh, at(0.0, 0.0, -0.01), {1.0, 0.0, 0.0}, options);
  }
  btRigidBody& ball = world.addSphere(kRadius, kBallMass, at(0.5 * kPeriod, 0.013, kRadius + 1e-4), {0.3, 0.0, 0.0});
  for (int k = 0; k < int(std::lround(seconds / kDt)); ++k) world.step(kDt);
  return positionOf(ball);
}

TEST(BallOnBoxFaces, ABallMeetsATexturedBoxAsTheSameReliefOnABoxMesh) {
  const double seconds = 1.0;
  const Eigen::Vector3d on_box = letDown(true, seconds), on_mesh = letDown(false, seconds);
  std::printf("[measured] after %.1f s: on the textured box (%.6f, %.6f, %.7f) m, on the slab mesh (%.6f, %.6f, %.7f) m\n",
              seconds, on_box.x(), on_box.y(), on_box.z(), on_mesh.x(), on_mesh.y(), on_mesh.z());
  EXPECT_LT((on_box - on_mesh).norm(), 1e-6);
  // Down in the groove: on its two ridges, sqrt(r^2 - (P/2)^2) over their top (4.583 mm).
  EXPECT_NEAR(on_box.z(), std::sqrt(kRadius * kRadius - 0.25 * kPeriod * kPeriod), 10e-6);
  EXPECT_NEAR(on_box.x(), 0.5 * kPeriod, 20e-6);
}

// The box a 1 kg body sliding across its grooves at 0.05 m/s on a frictionless plane, the ball
// in a groove moving with it: the ball stays in its groove at its height, the contact's held
// height taken against the box's own motion (StepContext::surface_body; against the world, the
// height moved 4.8 um).
TEST(BallOnBoxFaces, ABallInAGrooveIsCarriedAtItsHeightByTheSlidingBox) {
  const tex::TextureMap map = heightMap(128, kExtent, vGrooves);
  PhysicsWorld world;
  world.addPlainPlane(at(0.0, 0.0, -0.02), {0.0, 0.0, 0.0});
  btRigidBody& box = world.addTexturedBox(kSlabHalf, 1.0, at(0.0, 0.0, -0.01), {1.0, 0.0, 0.0}, facesOf(map));
  btRigidBody& ball = world.addSphere(kRadius, kBallMass, at(0.5 * kPeriod, 0.0, kRadius + 1e-4), {0.3, 0.0, 0.0});
  for (int k = 0; k < 200; ++k) world.step(kDt);
  const auto inBox = [&] { return Eigen::Vector3d(toEigen(box.getWorldTransform().inverse() * ball.getWorldTransform().getOrigin())); };
  const Eigen::Vector3d rest = inBox();
  const btVector3 v(0.05f, 0.0f, 0.0f);
  box.setLinearVelocity(v);
  ball.setLinearVelocity(v);
  double worst_height = 0.0, worst_across = 0.0;
  for (int k = 0; k < 500; ++k) {
    world.step(kDt);
    const Eigen::Vector3d offset = inBox() - rest;
    worst_height = std::max(worst_height, std::fabs(offset.z()));
    worst_across = std::max(worst_across, std::fabs(offset.x()));
  }
  std::printf("[measured] carried 25 mm across the grooves: its height in the box moved %.2f um at most, across %.1f um\n",
              worst_height * 1e6, worst_across * 1e6);
  EXPECT_GT(positionOf(box).x(), 0.02);
  EXPECT_LT(worst_height, 3e-6);
  EXPECT_LT(worst_across, 50e-6);
}

}  // namespace
}  // namespace thx::phys::test::test_ball_on_box_faces
