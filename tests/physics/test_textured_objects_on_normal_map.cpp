// Textured objects on a normal-mapped plane (issue 29; PhysicsWorld::addTexturedObjectsRelief): a
// ball with a bump map and a box with textured faces meet the relief the plane's normals integrate
// to, so both textures shape their contacts as on a relief plane, leaning by the map's mean slope;
// every other body still meets the normal-mapped plane.
#include <gtest/gtest.h>

#include <BulletCollision/NarrowPhaseCollision/btPersistentManifold.h>

#include <cmath>
#include <cstdio>

#include "tests/physics/textured_ball_scene.hpp"
#include "tests/support/sanitized_build.hpp"
#include "textures/height_from_normals.hpp"

namespace thx::phys::test::test_textured_objects_on_normal_map {
namespace {

using namespace textured_ball;

// `relief`'s normals alone: a normal map.
tex::TextureMap normalsOf(const tex::TextureMap& relief) {
  tex::TextureMap map(relief.width(), relief.height(), tex::Representation::Normal);
  for (int j = 0; j < map.height(); ++j)
    for (int i = 0; i < map.width(); ++i) map.setNormal(i, j, relief.normal(i, j));
  return map;
}

// A normal-mapped plane (`normals`, over `extent_m`) with its relief standing in for the textured
// objects, as physics-client builds it.
struct NormalMappedPlane {
  SurfaceHolder plane;
  tex::ReliefOfNormals relief;
  tex::TexturedSurface relief_surface;
  btRigidBody* plane_body = nullptr;
  btRigidBody* relief_body = nullptr;

  NormalMappedPlane(PhysicsWorld& world, tex::TextureMap normals, double extent_m, const BodyMaterial& material)
      : plane(holdSurface(std::move(normals), extent_m, false)),
        relief(tex::reliefFromNormals(*plane.map, Eigen::Vector2d::Constant(extent_m), tex::Address::Wrap)) {
    relief_surface = tex::TexturedSurface(relief.relief, plane.surface.mapping(), plane.surface.sampling(), true);
    plane_body = &world.addNormalMapPlane(plane.surface, material);
    relief_body = &world.addTexturedObjectsRelief(*plane_body, relief_surface, relief.mean_slope, material);
  }
};

// Whether a manifold between `a` and `b` exists (Bullet keeps a pair's manifold
// while their boxes overlap).
bool paired(PhysicsWorld& world, const btCollisionObject* a, const btCollisionObject* b) {
  btDispatcher& dispatcher = *world.world().getDispatcher();
  for (int m = 0; m < dispatcher.getNumManifolds(); ++m) {
    const btPersistentManifold* manifold = dispatcher.getManifoldByIndexInternal(m);
    if ((manifold->getBody0() == a && manifold->getBody1() == b) || (manifold->getBody0() == b && manifold->getBody1() == a))
      return true;
  }
  return false;
}

// A bumpy ball on a plane whose normal map is a bumpy relief's normals rests touching that relief
// where both reliefs touch, as on the relief plane itself (test_textured_ball.cpp: tip on tip);
// a plain ball beside it rests on the flat plane at its radius, and each meets only its own plane.
TEST(TexturedObjectsOnANormalMap, ABumpyBallMeetsTheReliefOfThePlanesNormalsAndAPlainBallThePlane) {
  const SurfaceHolder bumpy = holdSurface(bumpyPlane(256), 0.04, true);
  const double seconds = thx::test::kSanitized ? 2.5 : 3.0;
  const tex::TextureMap map = bumpMap(3e-4);
  const FaceTexture texture = ballTexture(map);
  PhysicsWorld world;
  const NormalMappedPlane plane(world, normalsOf(*bumpy.map), 0.04, {0.5, 0.0, 0.0});
  Eigen::Isometry3d pose = at(0.001, 0.0, kRadius + 2e-4);
  pose.linear() = (Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX()) * Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitY()))
                      .toRotationMatrix();
  btRigidBody& ball = world.addTexturedSphere(kRadius, kMass, pose, {0.5, 0.0, 0.0}, texture);
  btRigidBody& plain = world.addSphere(kRadius, kMass, at(0.05, 0.0, kRadius + 2e-4), {0.5, 0.0, 0.0});
  const int steps = int(std::lround(seconds / kDt));
  double fastest = 0.0;
  for (int k = 0; k < steps; ++k) {
    world.step(kDt);
    if (k >= steps - 500) fastest = std::max(fastest, velocityOf(ball).norm());
  }
  const Eigen::Isometry3d rest = toEigen(ball.getWorldTransform());
  // How far the ball stands above the bumpy relief itself and above the relief its normals
  // integrate to, at its lowest.
  const double gap = lowestGap(bumpy.surface, texture, rest);
  const double gap_integrated = lowestGap(plane.relief_surface, texture, rest);
  std::printf("[measured] bumpy ball on a normal map of bumps: %.2f um above the bumps' relief (%.2f above the relief "
              "the normals integrate to), centre at %.2f um, fastest over the last 0.5 s %.2f mm/s; plain ball at %.2f um\n",
              gap * 1e6, gap_integrated * 1e6, rest.translation().z() * 1e6, fastest * 1e3, positionOf(plain).z() * 1e6);
  // Within the bumpy relief's own rest on the relief plane (its bilinear reading: 11 um into the tips).
  EXPECT_NEAR(gap, 0.0, 1.5e-5);
  EXPECT_LT(fastest, 1.5e-3);
  // The plain ball on the normal-mapped plane: the flat plane carries it (normal_map_contact.hpp).
  EXPECT_NEAR(positionOf(plain).z(), kRadius, 2e-6);
  EXPECT_TRUE(paired(world, &ball, plane.relief_body));
  EXPECT_FALSE(paired(world, &ball, plane.plane_body));
  EXPECT_TRUE(paired(world, &plain, plane.plane_body));
  EXPECT_FALSE(paired(world, &plain, plane.relief_body));
}

// A uniformly tilted normal map (10 degrees, friction 0.1) slides a box at the virtual slope's
// acceleration g (tan t - mu) / (1 + mu tan t), holding its height: the plain box on the plane
// (test_box_friction.cpp), the textured box on the relief, level, its contacts leaning by the map's
// mean slope.
struct Slide {
  double accel = 0.0, expected = 0.0, z_error = 0.0, settled = 0.0;  // z_error: from its height once sliding
};
Slide slideOnATiltedNormalMap(bool textured_faces) {
  constexpr double kAngle = 10.0, kMu = 0.1, kHalf = 0.01;
  const tex::TextureMap tilted = tiltedMap(kAngle, 64, 0.2);
  PhysicsWorld world;
  const NormalMappedPlane plane(world, normalsOf(tilted), 0.2, {1.0, 0.0, 0.0});
  const tex::TextureMap faces_map = flatRelief(64);
  FaceTexture faces;
  faces.map = &faces_map;
  faces.tile_m = 2.0 * kHalf;
  // The tilted map's relief is flat (its depth 0), as are the box's faces: it rests at its half size.
  const double rest = kHalf;
  const Eigen::Isometry3d pose = at(0.0, 0.0, rest);
  btRigidBody& box = textured_faces ? world.addTexturedBox(Eigen::Vector3d::Constant(kHalf), 0.1, pose, {kMu, 0.0, 0.0}, faces)
                                    : world.addBox(Eigen::Vector3d::Constant(kHalf), 0.1, pose, {kMu, 0.0, 0.0});
  box.setActivationState(DISABLE_DEACTIVATION);
  Slide out;
  double v1 = 0.0, settled = 0.0;
  for (int k = 1; k <= 500; ++k) {
    world.step(kDt);
    if (k == 100) v1 = velocityOf(box).norm(), settled = positionOf(box).z();
    if (k >= 100) out.z_error = std::max(out.z_error, std::fabs(positionOf(box).z() - settled));
  }
  out.settled = settled - rest;
  out.accel = (velocityOf(box).norm() - v1) / 0.4;
  const double t = std::tan(kAngle * kPi / 180.0);
  out.expected = kG * (t - kMu) / (1.0 + kMu * t);
  EXPECT_EQ(paired(world, &box, plane.relief_body), textured_faces);
  EXPECT_EQ(paired(world, &box, plane.plane_body), !textured_faces);
  return out;
}

TEST(TexturedObjectsOnANormalMap, ATiltedMapSlidesATexturedBoxOnItsLeaningReliefAsThePlainBoxOnThePlane) {
  for (const bool textured : {false, true}) {
    const Slide s = slideOnATiltedNormalMap(textured);
    std::printf("[measured] %s box on a tilted normal map: a = %.4f m/s^2, expected %.4f (%+.2f %%), settled %.1f um off "
                "its half size, height held within %.2f um from there\n",
                textured ? "textured" : "plain", s.accel, s.expected, 100.0 * (s.accel / s.expected - 1.0), s.settled * 1e6,
                s.z_error * 1e6);
    EXPECT_NEAR(s.accel, s.expected, 0.015 * s.expected) << (textured ? "textured" : "plain");
    EXPECT_LT(std::fabs(s.settled), 1e-4) << (textured ? "textured" : "plain");
    EXPECT_LT(s.z_error, 5e-5) << (textured ? "textured" : "plain");
  }
}

}  // namespace
}  // namespace thx::phys::test::test_textured_objects_on_normal_map
