// A textured object on a plain plane (issue 29; clients/physics/plain_plane.hpp): a ball with a
// bump map and a grooved block meet PhysicsWorld::addPlainPlane by their own texture, on a smooth
// chart laid under them as on a plain box's face, where they used to collide as their coarse
// shapes. Plain objects, and every object on a normal-mapped plane, keep Bullet's convex-plane
// points.
#include <gtest/gtest.h>

#include <BulletCollision/CollisionShapes/btBoxShape.h>
#include <BulletCollision/CollisionShapes/btSphereShape.h>
#include <BulletCollision/CollisionShapes/btStaticPlaneShape.h>

#include <cmath>
#include <cstdio>

#include "clients/physics/plain_plane.hpp"
#include "clients/physics/textured_ball.hpp"
#include "tests/physics/grooved_block_scene.hpp"
#include "tests/physics/textured_ball_scene.hpp"

namespace thx::phys::test::test_textured_objects_on_plain_plane {
namespace {

namespace gb = grooved_block;
namespace tb = textured_ball;

TEST(TexturedObjectsOnAPlainPlane, OnlyThePlainPlaneIsMarkedForTheTextureRules) {
  PhysicsWorld world;
  const btRigidBody& plain = world.addPlainPlane(at(0.0, 0.0, 0.0), {1.0, 0.0, 0.0});
  const SurfaceHolder normals = holdSurface(flatRelief(16), 0.04, false);
  const btRigidBody& normal_mapped = world.addNormalMapPlane(normals.surface, {1.0, 0.0, 0.0});
  EXPECT_TRUE(isPlainPlane(*plain.getCollisionShape()));
  // A normal-mapped plane's textured objects meet the relief its normals integrate to
  // (addTexturedObjectsRelief), not the flat plane.
  EXPECT_FALSE(isPlainPlane(*normal_mapped.getCollisionShape()));
  btStaticPlaneShape unmarked(btVector3(0, 0, 1), 0);
  EXPECT_FALSE(isPlainPlane(unmarked));
}

TEST(TexturedObjectsOnAPlainPlane, ABallWithABumpMapRestsOnItAsOnAPlainBoxInEitherOrder) {
  // Recessed 0.5 mm everywhere, it rests on its recessed radius (as its coarse sphere: on its full one).
  const tex::TextureMap recess = tb::uniformRecess(5e-4);
  for (const bool ground_first : {true, false}) {
    const tb::Rested r =
        tb::restBallOn(tb::BallGround::PlainPlane, tb::ballTexture(recess), at(0.001, 0.0, tb::kRadius), 1.0, ground_first);
    std::printf("[measured] recessed ball on a plain plane (%s first): centre %.2f um from r - 0.5 mm, fastest %.3f mm/s\n",
                ground_first ? "plane" : "ball", (r.centre.z() - (tb::kRadius - 5e-4)) * 1e6, r.fastest_late * 1e3);
    EXPECT_NEAR(r.centre.z(), tb::kRadius - 5e-4, 5e-6);
    EXPECT_LT(r.fastest_late, 1e-4);
  }
  // With bumps (0.3 mm), turned so that no tip lies straight down: on their flanks, where it rests
  // on a plain box's face, and at rest (the plane first; the orders are compared above and below,
  // where a run costs less).
  const tb::Rested box = tb::restBumpyBallOn(tb::BallGround::PlainBox, 2.0);
  const tb::Rested plane = tb::restBumpyBallOn(tb::BallGround::PlainPlane, 2.0);
  std::printf("[measured] bumpy ball on a plain plane: %.2f um below r (on a plain box %.2f), %.2f um from where it "
              "rests on the box; fastest %.3f mm/s (on the box %.3f)\n",
              (tb::kRadius - plane.centre.z()) * 1e6, (tb::kRadius - box.centre.z()) * 1e6,
              (plane.centre - box.centre).norm() * 1e6, plane.fastest_late * 1e3, box.fastest_late * 1e3);
  EXPECT_LT(plane.centre.z(), tb::kRadius - 1e-4);  // on the bumps' flanks, not on the coarse sphere
  EXPECT_NEAR(plane.centre.z(), box.centre.z(), 2e-6);
  EXPECT_LT(plane.fastest_late, 0.05e-3);
}

TEST(TexturedObjectsOnAPlainPlane, AGroovedBlockRestsOnItsRidgesAndSlidesEitherWayAsOnAPlainBox) {
  // Its face's ridges, read at 0.31 mm texels, on the plane: within the bilinear rounding of a V's
  // crease below its coarse box's half height (half a texel of a 0.5 slope: 78 µm), where it rests
  // on a plain box; and half its weight moves it as friction alone would, along the grooves and
  // across them, the plane added before the block or after it.
  gb::Scene on_box(true, false, 128, {}, gb::BlockGround::PlainBox);
  for (int k = 0; k < 400; ++k) on_box.world->step(gb::kDt);
  const double box_height = positionOf(*on_box.block).z();
  const double friction_alone = 0.5 * (0.5 - 0.3) * kG * 0.04;
  for (const bool block_first : {true, false}) {
    gb::Scene rest(true, block_first, 128, {}, gb::BlockGround::PlainPlane);
    for (int k = 0; k < 400; ++k) rest.world->step(gb::kDt);
    gb::Scene along(true, block_first, 128, {}, gb::BlockGround::PlainPlane);
    gb::Scene across(true, block_first, 128, {}, gb::BlockGround::PlainPlane);
    const Eigen::Vector3d a = along.push({0.0, 0.5, 0.0}, 0.2);
    const Eigen::Vector3d c = across.push({0.5, 0.0, 0.0}, 0.2);
    const double height = positionOf(*rest.block).z();
    std::printf("[measured] grooved block on a plain plane (%s first): %.2f um below its half height (on a plain box "
                "%.2f); along %.2f mm, across %.2f mm (friction alone: %.1f)\n",
                block_first ? "block" : "plane", (gb::kHalf.z() - height) * 1e6, (gb::kHalf.z() - box_height) * 1e6,
                a.y() * 1e3, c.x() * 1e3, friction_alone * 1e3);
    EXPECT_LT(height, gb::kHalf.z() - 3e-5);  // its texture read, not its coarse box
    EXPECT_NEAR(height, box_height, 1e-6);
    EXPECT_NEAR(a.y(), friction_alone, 0.1 * friction_alone) << a.transpose();
    EXPECT_NEAR(c.x(), friction_alone, 0.1 * friction_alone) << c.transpose();
    EXPECT_LT(std::fabs(a.x()), 3e-4) << a.transpose();
    EXPECT_LT(std::fabs(c.y()), 3e-4) << c.transpose();
  }
}

// A plane tilted by `slope_deg` about y (downhill along +x in its own frame).
Eigen::Isometry3d tiltedPlane(double slope_deg) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = Eigen::AngleAxisd(deg(slope_deg), Eigen::Vector3d::UnitY()).toRotationMatrix();
  return pose;
}

TEST(TexturedObjectsOnAPlainPlane, OnATiltedPlaneTheRecessedBallRollsOnItsRecessedRadius) {
  // Rolling without slipping on rho = r - 0.5 mm with the coarse ball's inertia: 3 % below the
  // coarse ball's 5/7 g sin(slope) (TexturedBall.AUniformlyRecessedBallRestsAndRollsOnItsRecessedSurface
  // on a relief plane, there with gravity tilted; here the plane itself).
  const double depth = 5e-4, slope = 5.0, seconds = 0.3, rho = tb::kRadius - depth;
  const tex::TextureMap recess = tb::uniformRecess(depth);
  const FaceTexture texture = tb::ballTexture(recess);
  const Eigen::Isometry3d plane = tiltedPlane(slope);
  const auto speedAfter = [&](bool textured) {
    PhysicsWorld world;
    world.addPlainPlane(plane, {0.5, 0.0, 0.0});
    const Eigen::Isometry3d pose = plane * at(0.0, 0.0, textured ? rho : tb::kRadius);
    btRigidBody& ball = textured ? world.addTexturedSphere(tb::kRadius, tb::kMass, pose, {0.5, 0.0, 0.0}, texture)
                                 : world.addSphere(tb::kRadius, tb::kMass, pose, {0.5, 0.0, 0.0});
    for (int k = 0; k < int(std::lround(seconds / tb::kDt)); ++k) world.step(tb::kDt);
    return velocityOf(ball).norm();
  };
  const double expected = kG * std::sin(deg(slope)) / (1.0 + 0.4 * tb::kRadius * tb::kRadius / (rho * rho)) * seconds;
  const double coarse = 5.0 / 7.0 * kG * std::sin(deg(slope)) * seconds;
  const double recessed = speedAfter(true), plain = speedAfter(false);
  std::printf("[measured] down a 5 deg plain plane in 0.3 s: the recessed ball %.5f m/s (%.2f %% from rolling on its "
              "recessed radius), the plain ball %.5f (%.2f %% from 5/7 g sin)\n",
              recessed, 100.0 * (recessed / expected - 1.0), plain, 100.0 * (plain / coarse - 1.0));
  EXPECT_NEAR(recessed, expected, 0.002 * expected);
  EXPECT_NEAR(plain, coarse, 0.002 * coarse);
}

TEST(TexturedObjectsOnAPlainPlane, OnATiltedPlaneTheGroovedBlockSlidesAsThePlainBlock) {
  // 10 degrees, friction 0.1 (Bullet multiplies the plane's 1 by the block's): g (sin - mu cos),
  // standing on its ridges as the plain block stands on its face.
  const double slope = 10.0, mu = 0.1;
  const tex::TextureMap grooves = heightMap(128, gb::kExtent, gb::vGrooves);
  FaceTexture faces;
  faces.map = &grooves;
  faces.tile_m = gb::kExtent;
  const Eigen::Isometry3d plane = tiltedPlane(slope);
  const auto acceleration = [&](bool textured) {
    PhysicsWorld world;
    world.addPlainPlane(plane, {1.0, 0.0, 0.0});
    const Eigen::Isometry3d pose = plane * at(0.0, 0.0, gb::kHalf.z() + 1e-5);
    btRigidBody& block = textured ? world.addTexturedBox(gb::kHalf, gb::kMass, pose, {mu, 0.0, 0.0}, faces)
                                  : world.addBox(gb::kHalf, gb::kMass, pose, {mu, 0.0, 0.0});
    for (int k = 0; k < 100; ++k) world.step(gb::kDt);
    const double v0 = velocityOf(block).norm();
    for (int k = 0; k < 300; ++k) world.step(gb::kDt);
    return (velocityOf(block).norm() - v0) / (300 * gb::kDt);
  };
  const double expected = kG * (std::sin(deg(slope)) - mu * std::cos(deg(slope)));
  const double grooved = acceleration(true), plain = acceleration(false);
  std::printf("[measured] down a 10 deg plain plane, friction 0.1: the grooved block %.4f m/s^2, the plain block %.4f "
              "(g (sin - mu cos) %.4f)\n",
              grooved, plain, expected);
  EXPECT_NEAR(grooved, expected, 0.01 * expected);
  EXPECT_NEAR(plain, expected, 0.01 * expected);
}

TEST(TexturedObjectsOnAPlainPlane, AnObjectHoldingMoreTexelsThanTheBudgetMeetsItAsItsCoarseShape) {
  // The 2 x 2 cm grooved block at 0.31 mm texels: 64 x 64 under its largest face; the dimpled
  // ball's cap within reach at its 61 um texels, some 7,500; the 20 x 20 x 2 cm slab of the tests
  // 640 x 640, over the budget.
  const tex::TextureMap grooves = heightMap(128, gb::kExtent, gb::vGrooves);
  FaceTexture faces;
  faces.map = &grooves;
  faces.tile_m = gb::kExtent;
  btBoxShape block(toBt(gb::kHalf)), slab(toBt(gb::kSlabHalf));
  attachFaceTexture(block, faces);
  attachFaceTexture(slab, faces);
  const tex::TextureMap dimples = tb::dimpleMap();
  const FaceTexture dimpled = tb::ballTexture(dimples);
  btSphereShape ball{btScalar(tb::kRadius)}, plain_ball{btScalar(tb::kRadius)};
  attachBallTexture(ball, dimpled);
  std::printf("[measured] texels under a textured object on a plain plane: block %.0f, dimpled ball %.0f, slab %.0f "
              "(budget %.0f)\n",
              plainPlaneTexels(block), plainPlaneTexels(ball), plainPlaneTexels(slab), kPlainPlaneTexelBudget);
  EXPECT_NEAR(plainPlaneTexels(block), 64.0 * 64.0, 1.0);
  EXPECT_GT(plainPlaneTexels(ball), 1000.0);
  EXPECT_LT(plainPlaneTexels(ball), kPlainPlaneTexelBudget);
  EXPECT_NEAR(plainPlaneTexels(slab), 640.0 * 640.0, 100.0);
  EXPECT_EQ(plainPlaneTexels(plain_ball), 0.0);
  // The slab let down on the plane rests on its coarse box's face, its grooves unread.
  PhysicsWorld world;
  world.addPlainPlane(at(0.0, 0.0, 0.0), {1.0, 0.0, 0.0});
  btRigidBody& body = world.addTexturedBox(gb::kSlabHalf, gb::kSlabMass, at(0.0, 0.0, gb::kSlabHalf.z() + 1e-5),
                                           {1.0, 0.0, 0.0}, faces);
  for (int k = 0; k < 200; ++k) world.step(gb::kDt);
  EXPECT_NEAR(positionOf(body).z(), gb::kSlabHalf.z(), 1e-6);
}

TEST(TexturedObjectsOnAPlainPlane, ABallWithItsTexelGridMeetsItByItsTextureBeyondTheRastersBudget) {
  // The dimpled ball with its map at 512 texels a face holds some 29,000 texels by the raster's
  // count, over its budget: laid by addTexturedSphere (its texel grid) it meets the plane on its
  // own texels and rests in a dimple as the 256-texel ball does (measured 127.0 and 127.5 µm
  // into its radius); attached by hand without a grid it would meet the plane as a smooth sphere
  // (until 2026-12-07, evening, every ball did at 384 texels a face and more).
  const tex::TextureMap fine = heightMap(512, tb::kTile, tb::dimples);
  const tex::TextureMap coarse = tb::dimpleMap();
  const FaceTexture fine_texture = tb::ballTexture(fine);
  btSphereShape by_hand{btScalar(tb::kRadius)};
  attachBallTexture(by_hand, fine_texture);
  EXPECT_GT(plainPlaneTexels(by_hand), kPlainPlaneTexelBudget);
  EXPECT_EQ(plainPlaneTexelBudget(by_hand), kPlainPlaneTexelBudget);
  PhysicsWorld world;
  world.addPlainPlane(at(0.0, 0.0, 0.0), {0.5, 0.0, 0.0});
  btRigidBody& fine_ball =
      world.addTexturedSphere(tb::kRadius, tb::kMass, at(-0.03, 0.0, tb::kRadius + 1e-4), {0.5, 0.0, 0.0}, fine_texture);
  btRigidBody& coarse_ball =
      world.addTexturedSphere(tb::kRadius, tb::kMass, at(0.03, 0.0, tb::kRadius + 1e-4), {0.5, 0.0, 0.0}, tb::ballTexture(coarse));
  EXPECT_EQ(plainPlaneTexelBudget(*fine_ball.getCollisionShape()), kGriddedBallPlainPlaneTexelBudget);
  EXPECT_LT(plainPlaneTexels(*fine_ball.getCollisionShape()), kGriddedBallPlainPlaneTexelBudget);
  for (int k = 0; k < 300; ++k) world.step(tb::kDt);
  const double fine_z = positionOf(fine_ball).z(), coarse_z = positionOf(coarse_ball).z();
  std::printf("[measured] dimpled ball on a plain plane, 512 and 256 texels a face: %.2f and %.2f um into its radius\n",
              (tb::kRadius - fine_z) * 1e6, (tb::kRadius - coarse_z) * 1e6);
  EXPECT_LT(fine_z, tb::kRadius - 100e-6);
  EXPECT_NEAR(fine_z, coarse_z, 2e-6);
}

TEST(TexturedObjectsOnAPlainPlane, APlainBallAndAPlainBoxKeepBulletsPoints) {
  // Bullet's sphere on the plane: at its radius to float rounding; its box: four points at its
  // bottom face's corners (the smooth chart's quarters would lie a hair inside them).
  PhysicsWorld world;
  world.addPlainPlane(at(0.0, 0.0, 0.0), {1.0, 0.0, 0.0});
  btRigidBody& ball = world.addSphere(tb::kRadius, tb::kMass, at(0.05, 0.0, tb::kRadius + 1e-4), {0.5, 0.0, 0.0});
  world.addBox(gb::kHalf, gb::kMass, at(-0.05, 0.0, gb::kHalf.z() + 1e-5), {0.3, 0.0, 0.0});
  for (int k = 0; k < 300; ++k) world.step(gb::kDt);
  EXPECT_NEAR(positionOf(ball).z(), tb::kRadius, 1e-6);
  btDispatcher& dispatcher = *world.world().getDispatcher();
  int corners = 0;
  for (int m = 0; m < dispatcher.getNumManifolds(); ++m) {
    const btPersistentManifold& manifold = *dispatcher.getManifoldByIndexInternal(m);
    for (int k = 0; k < manifold.getNumContacts(); ++k) {
      const Eigen::Vector3d p = toEigen(manifold.getContactPoint(k).getPositionWorldOnB());
      if (p.x() < 0.0 && std::fabs(std::fabs(p.x() + 0.05) - gb::kHalf.x()) < 1e-6 &&
          std::fabs(std::fabs(p.y()) - gb::kHalf.y()) < 1e-6)
        ++corners;
    }
  }
  EXPECT_EQ(corners, 4);
}

}  // namespace
}  // namespace thx::phys::test::test_textured_objects_on_plain_plane
