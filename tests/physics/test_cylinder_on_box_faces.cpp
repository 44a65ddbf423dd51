// A cylinder against a textured box (box_ground.hpp): the box's faces met as a relief mesh's on
// the chart under the cylinder, by the rod rules of the relief plane (relief_collision.hpp). The
// grooves of grooved_block_scene.hpp (V-grooves, 4 mm apart, 1 mm deep, along y on the top face)
// on a fixed 0.2 x 0.2 x 0.02 m box and on the 2 x 2 x 1 cm, 50 g block; held to the relief
// plane's answers and the analytic ones of rod_in_groove_scene.hpp. Before, a cylinder met the
// coarse box.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

#include "tests/physics/pen_pushes_block.hpp"
#include "tests/physics/rod_in_groove_scene.hpp"

namespace thx::phys::test::test_cylinder_on_box_faces {
namespace {

using namespace grooved_block;
using namespace rod_in_groove;

FaceTexture facesOf(const tex::TextureMap& map) {
  FaceTexture faces;
  faces.map = &map;
  faces.tile_m = kExtent;
  return faces;
}

TEST(CylinderOnBoxFaces, LyingInAGrooveItRestsAsOnTheReliefPlane) {
  const RodScene on_plane(Ground::Plane, Rod::LyingCylinder), on_box(Ground::Box, Rod::LyingCylinder);
  std::printf("[measured] lying in a groove: on the box %.4f mm over the ridges at x %.4f mm, on the plane %.4f mm at "
              "%.4f mm (both walls: %.4f mm)\n",
              on_box.rest.z() * 1e3, on_box.rest.x() * 1e3, on_plane.rest.z() * 1e3, on_plane.rest.x() * 1e3,
              inTheGroove(kRadius) * 1e3);
  EXPECT_NEAR(on_box.rest.z(), on_plane.rest.z(), 1e-6) << on_box.rest.transpose();
  EXPECT_NEAR(on_box.rest.x(), on_plane.rest.x(), 1e-6) << on_box.rest.transpose();
  EXPECT_NEAR(on_box.rest.y(), on_plane.rest.y(), 1e-5) << on_box.rest.transpose();
  // Before, on the coarse box: its radius over the ridges.
  EXPECT_LT(on_box.rest.z(), kRadius - 0.5 * kDepth);
}

TEST(CylinderOnBoxFaces, PushedAcrossItLeavesTheGrooveOnlyAboveTanWallOfItsWeight) {
  for (const double force : {0.4, 0.6}) {
    const Eigen::Vector3d on_box = RodScene(Ground::Box, Rod::LyingCylinder).push(force);
    const Eigen::Vector3d on_plane = RodScene(Ground::Plane, Rod::LyingCylinder).push(force);
    std::printf("[measured] pushed across at %.1f of its weight for 0.3 s: on the box %.3f mm, on the plane %.3f mm\n",
                force, on_box.x() * 1e3, on_plane.x() * 1e3);
    EXPECT_LT((on_box - on_plane).norm(), 1e-4) << force << ": " << on_box.transpose() << " / " << on_plane.transpose();
    if (force < std::tan(kWall)) {
      EXPECT_LT(on_box.norm(), 1e-4) << on_box.transpose();
    } else {
      EXPECT_GT(on_box.x(), 2 * kPeriod) << on_box.transpose();
    }
  }
}

TEST(CylinderOnBoxFaces, OnItsEndFaceItStandsOnTheRidgesAsOnThePlane) {
  const RodScene on_plane(Ground::Plane, Rod::StandingCylinder), on_box(Ground::Box, Rod::StandingCylinder);
  std::printf("[measured] standing on its end face: on the box %.4f mm, on the plane %.4f mm\n", on_box.rest.z() * 1e3,
              on_plane.rest.z() * 1e3);
  EXPECT_NEAR(on_box.rest.z(), on_plane.rest.z(), 1e-6) << on_box.rest.transpose();
  const Eigen::Vector3d axis = toEigen(on_box.rod->getWorldTransform().getBasis().getColumn(2));
  EXPECT_GT(axis.z(), std::cos(deg(0.5)));
  EXPECT_LT(toEigen(on_box.rod->getLinearVelocity()).norm(), 1e-3);
}

// Lying across the grooves, on their ridges as the texel centres sample them (up to half a texel
// times the walls' slope, 78 µm, below their tops), on the box as on the plane.
TEST(CylinderOnBoxFaces, LyingAcrossTheGroovesItRestsOnTheirRidges) {
  const tex::TextureMap map = heightMap(128, kExtent, vGrooves);
  SurfaceHolder plane(holdSurface(heightMap(128, kExtent, vGrooves), kExtent, true));
  Eigen::Vector3d rest[2];
  for (const bool on_box : {false, true}) {
    PhysicsWorld world;
    if (on_box) {
      world.addTexturedBox(kSlabHalf, 0.0, at(0.0, 0.0, -kSlabHalf.z()), {1.0, 0.0, 0.0}, facesOf(map));
    } else {
      world.addReliefPlane(plane.surface, {1.0, 0.0, 0.0});
    }
    Eigen::Isometry3d pose = at(0.0, 0.013, kRadius + 2e-4);
    pose.linear() = Eigen::AngleAxisd(0.5 * kPi, Eigen::Vector3d::UnitY()).toRotationMatrix();
    btRigidBody& rod = world.addCylinder(kRadius, kHalfLength, kRodMass, pose, {kFriction, 0.0, 0.0});
    for (int k = 0; k < 1000; ++k) world.step(kDt);
    rest[on_box] = positionOf(rod);
    EXPECT_LT(toEigen(rod.getLinearVelocity()).norm(), 1e-4) << on_box;
  }
  std::printf("[measured] lying across the grooves: on the box %.4f mm over the ridges, on the plane %.4f mm\n",
              rest[1].z() * 1e3, rest[0].z() * 1e3);
  EXPECT_NEAR(rest[1].z(), rest[0].z(), 1e-6);
  EXPECT_NEAR(rest[1].x(), rest[0].x(), 1e-6);
  EXPECT_LT(rest[1].z(), kRadius + 1e-6);
  EXPECT_GT(rest[1].z(), kRadius - 0.5 * kExtent / 128 * std::tan(kWall));
}

// An upright cylinder as the pen (pen_pushes_block.hpp): as the pen's capsule does, it sits in an
// upright groove of the side face and feels its walls; level grooves and a plain face let it
// slide. Its chart is laid under its axis's point nearest the block's centre (relief_collision.cpp,
// meshCollision): laid under its centre, over the block's top edge, it met the side on a chart
// across that crease, slid 3 mm along the face out of its groove and the block rose at 0.018 m/s.
TEST(CylinderOnBoxFaces, AnUprightCylinderPushingTheGroovedBlockDragsItAcrossItsGroovesAndSlidesAlongThem) {
  expectThePenFeelsUprightGroovesOnly(PenShape::Cylinder);
}

// The grooved block laid on two fixed cylinders (rails) along its grooves, each in a groove of
// its bottom face: the box is the ground over the cylinders (its -z face's chart faces down).
struct OnRails {
  Eigen::Vector3d rest, pushed;
};
OnRails blockOnRails(const Eigen::Vector3d& force_over_weight, bool rails_first) {
  const tex::TextureMap map = heightMap(128, kExtent, vGrooves);
  PhysicsWorld world;
  Eigen::Isometry3d rail = at(0.0, 0.0, kRadius);
  rail.linear() = Eigen::AngleAxisd(0.5 * kPi, Eigen::Vector3d::UnitX()).toRotationMatrix();
  const auto add_rails = [&] {
    for (const double x : {-1.5 * kPeriod, 1.5 * kPeriod}) {
      rail.translation().x() = x;
      world.addCylinder(kRadius, 0.03, 0.0, rail, {1.0, 0.0, 0.0});
    }
  };
  if (rails_first) add_rails();
  // The block's bottom ridges at x = k P in its frame: its floors at +-1.5 P over the rails.
  btRigidBody& block = world.addTexturedBox(kHalf, kMass, at(0.0, 0.0, 2 * kRadius + kHalf.z() + 2e-4),
                                            {kFriction, 0.0, 0.0}, facesOf(map));
  if (!rails_first) add_rails();
  for (int k = 0; k < 300; ++k) world.step(kDt);
  OnRails r;
  r.rest = positionOf(block);
  r.pushed = pushBlock(world, block, force_over_weight, 0.2);
  return r;
}

TEST(CylinderOnBoxFaces, AGroovedBlockOnTwoRailsInItsGroovesSlidesAlongThemAndIsHeldAcross) {
  const OnRails along = blockOnRails({0.0, 0.5, 0.0}, true), across = blockOnRails({0.5, 0.0, 0.0}, true);
  const OnRails along_other_order = blockOnRails({0.0, 0.5, 0.0}, false);
  // Each rail touches both walls of its groove: the block's bottom r / cos(wall) - D over the
  // rails' axes; pushed along, friction on both walls (their normal forces sum to W / cos(wall)).
  const double fit = kRadius + inTheGroove(kRadius) + kHalf.z();
  const double slid = 0.5 * (0.5 - kFriction / std::cos(kWall)) * kG * 0.04;
  std::printf("[measured] on two rails in its grooves: at rest %.4f mm over the rails' axes (both walls: %.4f), x %.4f mm; "
              "pushed along at 0.5 of its weight for 0.2 s %.2f mm (friction on both walls: %.2f), off its line %.4f mm; "
              "across %.4f mm; the other order of adding %.2f mm\n",
              (along.rest.z() - kRadius) * 1e3, (fit - kRadius) * 1e3, along.rest.x() * 1e3, along.pushed.y() * 1e3,
              slid * 1e3, along.pushed.x() * 1e3, across.pushed.norm() * 1e3, along_other_order.pushed.y() * 1e3);
  // The texels' sampling leaves a rod 16 µm high in a groove (ARodAlongAGrooveRestsWhereItsCircleTouchesBothWalls).
  EXPECT_NEAR(along.rest.z(), fit, 2.5e-5);
  EXPECT_NEAR(along.rest.x(), 0.0, 1e-5);
  EXPECT_NEAR(along.pushed.y(), slid, 0.1 * slid);
  EXPECT_LT(std::fabs(along.pushed.x()), 1e-4);
  EXPECT_LT(across.pushed.norm(), 0.25 * kPeriod);
  // Bullet's solver visits the two rails' manifolds in the order they were added: 3.5 µm apart.
  EXPECT_LT((along_other_order.pushed - along.pushed).norm(), 1e-5);
}

// A cylinder lying across the grooves with its middle 2 mm past the fixed box's +x edge, where a
// ridge runs: it tips over the edge and slides off outwards, as off a plain box. Before the rod's
// normal at a convex edge (edge_contact.hpp) the top's contact at the edge pushed straight up and
// friction held the rod there as on a hinge: it swung under the edge and fell moving back towards
// the box at 7 mm/s.
struct OffTheEdge {
  double drop_m = 0.0, moved_out_m = 0.0, fastest_up = 0.0, slowest_out = 0.0;
};
OffTheEdge tipOverTheEdge(bool textured) {
  const tex::TextureMap map = heightMap(128, kExtent, vGrooves);
  PhysicsWorld world;
  const Eigen::Isometry3d box = at(0.0, 0.0, -kSlabHalf.z());
  if (textured) {
    world.addTexturedBox(kSlabHalf, 0.0, box, {1.0, 0.0, 0.0}, facesOf(map));
  } else {
    world.addBox(kSlabHalf, 0.0, box, {1.0, 0.0, 0.0});
  }
  Eigen::Isometry3d pose = at(kSlabHalf.x() + 0.002, 0.013, kRadius + 1e-5);
  pose.linear() = Eigen::AngleAxisd(0.5 * kPi, Eigen::Vector3d::UnitY()).toRotationMatrix();
  btRigidBody& rod = world.addCylinder(kRadius, kHalfLength, kRodMass, pose, {kFriction, 0.0, 0.0});
  OffTheEdge off;
  for (int k = 0; k < 200; ++k) {
    world.step(kDt);
    off.fastest_up = std::max(off.fastest_up, double(rod.getLinearVelocity().z()));
    off.slowest_out = std::min(off.slowest_out, double(rod.getLinearVelocity().x()));
  }
  off.drop_m = kRadius - positionOf(rod).z();
  off.moved_out_m = positionOf(rod).x() - pose.translation().x();
  return off;
}

TEST(CylinderOnBoxFaces, LyingPastTheBoxsEdgeItTipsOverAndSlidesOffOutwards) {
  const OffTheEdge textured = tipOverTheEdge(true), plain = tipOverTheEdge(false);
  std::printf("[measured] past the edge, after 0.2 s: off the grooved box fallen %.1f mm, moved out %.2f mm, fastest up "
              "%.4f m/s, fastest back towards the box %.4f m/s; off the plain box %.1f mm, %.2f mm, %.4f m/s, %.4f m/s\n",
              textured.drop_m * 1e3, textured.moved_out_m * 1e3, textured.fastest_up, -textured.slowest_out,
              plain.drop_m * 1e3, plain.moved_out_m * 1e3, plain.fastest_up, -plain.slowest_out);
  for (const OffTheEdge& off : {textured, plain}) {
    EXPECT_GT(off.drop_m, 0.05);
    EXPECT_GT(off.moved_out_m, 0.003);
    EXPECT_GT(off.slowest_out, -1e-3);
    EXPECT_LT(off.fastest_up, 0.01);
  }
}

}  // namespace
}  // namespace thx::phys::test::test_cylinder_on_box_faces
