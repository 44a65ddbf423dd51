// Untextured boxes, capsules and cylinders on a relief-textured mesh meet the relief as on the
// relief plane (issue 29, "as the plane does today"; relief_collision.hpp): the plane's rule on the
// mesh's chart under the object, the relief standing on the mesh's bend. Held to the analytic
// answers of a rod in a V-groove (rod_in_groove_scene.hpp) on a flat mesh and on a pipe's grooved
// inside, and to the relief plane's own answer. Before, Bullet's triangles held them on the smooth
// surface with the texture's normal read at one point.
#include <BulletCollision/CollisionShapes/btBoxShape.h>
#include <BulletCollision/CollisionShapes/btCapsuleShape.h>
#include <BulletCollision/CollisionShapes/btCylinderShape.h>
#include <BulletCollision/CollisionShapes/btSphereShape.h>
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "clients/physics/relief_collision.hpp"
#include "tests/physics/rod_in_groove_scene.hpp"

namespace thx::phys::test::test_plain_objects_on_relief_mesh {
namespace {

using namespace grooved_block;
using namespace rod_in_groove;

TEST(PlainObjectsOnReliefMesh, TheRuleTakesBoxesCapsulesAndCylindersNotBalls) {
  RodScene scene(Ground::Trough, Rod::Capsule);
  const btCollisionShape& mesh_shape = *scene.world->world().getCollisionObjectArray()[0]->getCollisionShape();
  ASSERT_NE(meshReliefOf(mesh_shape), nullptr);
  btBoxShape box(btVector3(0.01f, 0.01f, 0.01f));
  btCapsuleShapeZ capsule(0.003f, 0.02f);
  btCylinderShapeZ cylinder(btVector3(0.003f, 0.003f, 0.01f));
  btSphereShape ball(0.005f);
  EXPECT_TRUE(reliefTakesMeshPair(box, mesh_shape));
  EXPECT_TRUE(reliefTakesMeshPair(capsule, mesh_shape));
  EXPECT_TRUE(reliefTakesMeshPair(cylinder, mesh_shape));
  // A ball keeps Bullet's sphere-triangle points, lifted onto the relief (mesh_contact.hpp).
  EXPECT_FALSE(reliefTakesMeshPair(ball, mesh_shape));
  // A mesh without a relief has no chart to meet.
  EXPECT_FALSE(reliefTakesMeshPair(box, box));
}

TEST(PlainObjectsOnReliefMesh, ARodAlongAGrooveRestsWhereItsCircleTouchesBothWalls) {
  const RodScene on_plane(Ground::Plane, Rod::Capsule), flat(Ground::FlatMesh, Rod::Capsule),
      trough(Ground::Trough, Rod::Capsule);
  // The texels' sampling leaves it 16 µm high on the plane at 0.31 mm texels (8 µm at 0.16 mm:
  // bench_rod_in_groove).
  EXPECT_NEAR(on_plane.rest.z(), inTheGroove(kRadius), 2.5e-5) << on_plane.rest.transpose();
  EXPECT_NEAR(on_plane.rest.x(), 0.5 * kPeriod, 1e-5);
  // A flat mesh's chart is the plane: the same answer.
  EXPECT_NEAR(flat.rest.z(), on_plane.rest.z(), 1e-6) << flat.rest.transpose();
  EXPECT_NEAR(std::fabs(flat.rest.x() - on_plane.rest.x()), 0.0, 1e-5);
  // In the pipe the groove's floor stands on the bend (19 µm up, 2 mm from the bottom line) and
  // its walls lean by the bend's slope (1.1 degrees): the same rule within a few texel-sampling
  // errors (25 µm).
  const double bend = 0.5 * trough.rest.x() * trough.rest.x() / kTroughRadius;
  RecordProperty("trough_above_theory_um", int(std::lround((trough.rest.z() - inTheGroove(kRadius) - bend) * 1e6)));
  EXPECT_NEAR(trough.rest.z(), inTheGroove(kRadius) + bend, 3.5e-5) << trough.rest.transpose();
  EXPECT_NEAR(trough.rest.x(), 0.5 * kPeriod, 1e-4);
  // Before plain objects met the relief, it lay on the smooth surface: r above the ridges.
  EXPECT_LT(trough.rest.z(), kRadius - 0.5 * kDepth);
}

TEST(PlainObjectsOnReliefMesh, ACylinderOnItsSideRestsAsTheCapsuleOfItsRadius) {
  // Both touch along the same two lines, one on each wall (selectLyingRodContacts); before, the
  // cylinder was held by one wall at one end and rested 54 µm into the walls.
  for (const Ground ground : {Ground::Plane, Ground::Trough}) {
    const RodScene capsule(ground, Rod::Capsule), cylinder(ground, Rod::LyingCylinder);
    EXPECT_NEAR(cylinder.rest.z(), capsule.rest.z(), 1e-6) << int(ground);
    EXPECT_NEAR(cylinder.rest.x(), capsule.rest.x(), 1e-6) << int(ground);
    // Not walked along the groove by its contacts.
    EXPECT_NEAR(cylinder.rest.y(), capsule.rest.y(), 1e-5) << int(ground);
  }
}

TEST(PlainObjectsOnReliefMesh, PushedAcrossARodLeavesTheGrooveOnlyAboveTanWallOfItsWeight) {
  for (const Ground ground : {Ground::FlatMesh, Ground::Trough}) {
    for (const Rod kind : {Rod::Capsule, Rod::LyingCylinder}) {
      const Eigen::Vector3d held = RodScene(ground, kind).push(0.4);
      const Eigen::Vector3d leaves = RodScene(ground, kind).push(0.6);
      EXPECT_LT(held.norm(), 1e-4) << int(ground) << " " << int(kind) << ": " << held.transpose();
      EXPECT_GT(leaves.x(), 2 * kPeriod) << int(ground) << " " << int(kind) << ": " << leaves.transpose();
    }
  }
}

TEST(PlainObjectsOnReliefMesh, ACylinderOnItsEndFaceStandsOnTheRidgesAsOnThePlane) {
  const RodScene on_plane(Ground::Plane, Rod::StandingCylinder), flat(Ground::FlatMesh, Rod::StandingCylinder);
  // On the ridges as the texel centres sample them: up to half a texel times the walls' slope
  // (78 µm) below their tops.
  EXPECT_LT(on_plane.rest.z(), kHalfLength + 1e-6);
  EXPECT_GT(on_plane.rest.z(), kHalfLength - 0.5 * kExtent / 128 * std::tan(kWall)) << on_plane.rest.transpose();
  EXPECT_NEAR(flat.rest.z(), on_plane.rest.z(), 2e-6) << flat.rest.transpose();
  const Eigen::Vector3d axis = toEigen(flat.rod->getWorldTransform().getBasis().getColumn(2));
  EXPECT_GT(axis.z(), std::cos(deg(0.5)));
  EXPECT_LT(toEigen(flat.rod->getLinearVelocity()).norm(), 1e-3);
}


// A rod lying across ground that bulges under its middle: across the top of a horizontal log (a
// cylinder mesh of radius R, square to it) it rests with its axis R + r from the log's, stably
// (rocking along its length raises it: r < R). Its contacts at its ends alone (where the
// candidates within the breaking threshold end) let it sink: before a capsule's middle was taken
// as a cylinder's is (selectLyingRodContacts), a capsule across a 2 cm log with a flat relief sank
// 2.4 mm and across a 1 cm log it was thrown a metre up; across the top of a 5 cm sphere's smooth
// chart it rested 60 um into it. Let down `offset` along its axis from the top, it rocks there,
// rolling on the log (for 2 s; `first_high_m`, `last_high_m`: its centre's highest over R + r in
// the first and the last half second).
struct AcrossABulge {
  double off_m = 0.0, along_m = 0.0, speed = 0.0, first_high_m = 0.0, last_high_m = 0.0;
};
AcrossABulge lieAcross(bool sphere, double R, bool relief, Rod kind, double offset = 0.0) {
  const tex::TextureMap flat = heightMap(256, kExtent, [](double, double) { return 0.0; });
  const mesh::GeneratedMesh ground = sphere ? mesh::sphere(R, 48, 24, kExtent) : mesh::cylinder(R, 0.1, 64, 4, kExtent);
  PhysicsWorld world;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  if (!sphere) {  // the log's axis along y, its middle under the rod
    pose.linear() = Eigen::AngleAxisd(-0.5 * kPi, Eigen::Vector3d::UnitX()).toRotationMatrix();
    pose.translation() = Eigen::Vector3d(0.0, -0.05, 0.0);
  }
  MeshContactOptions options;
  if (relief) {
    options.texture = &flat;
    options.normals_made_for_m = Eigen::Vector2d::Constant(kExtent);
  }
  world.addTexturedMesh(ground.mesh, pose, {1.0, 0.0, 0.0}, options);
  Eigen::Isometry3d start = at(offset, 0.0, R + kRadius + 2e-4);
  start.linear() = Eigen::AngleAxisd(0.5 * kPi, Eigen::Vector3d::UnitY()).toRotationMatrix();  // along x
  btRigidBody& rod = kind == Rod::Capsule ? world.addCapsule(kRadius, kHalfLength, kRodMass, start, {kFriction, 0.0, 0.0})
                                          : world.addCylinder(kRadius, kHalfLength, kRodMass, start, {kFriction, 0.0, 0.0});
  rod.setActivationState(DISABLE_DEACTIVATION);
  const int steps = offset != 0.0 ? 2000 : 500;
  AcrossABulge a;
  a.first_high_m = a.last_high_m = -1.0;
  for (int k = 0; k < steps; ++k) {
    world.step(kDt);
    const double high = positionOf(rod).z() - R - kRadius;
    if (k >= 100 && k < 600) a.first_high_m = std::max(a.first_high_m, high);  // once let down
    if (k >= steps - 500) a.last_high_m = std::max(a.last_high_m, high);
  }
  const Eigen::Vector3d c = positionOf(rod);
  const double from_axis = sphere ? c.norm() : Eigen::Vector2d(c.x(), c.z()).norm();
  a.off_m = from_axis - R - kRadius, a.along_m = c.x(), a.speed = double(rod.getLinearVelocity().length());
  return a;
}

TEST(PlainObjectsOnReliefMesh, ARodLyingAcrossALogOrASphereRestsOnItsTop) {
  for (const Rod kind : {Rod::Capsule, Rod::LyingCylinder}) {
    const char* name = kind == Rod::Capsule ? "capsule" : "cylinder";
    for (const double R : {0.01, 0.02}) {
      for (const bool relief : {false, true}) {
        const AcrossABulge a = lieAcross(false, R, relief, kind);
        std::printf("[measured] %s across a %.0f mm log (%s): axis %+.2f um from R + r, %.3f mm along, %.1e m/s\n", name,
                    R * 1e3, relief ? "flat relief" : "smooth chart", a.off_m * 1e6, a.along_m * 1e3, a.speed);
        EXPECT_NEAR(a.off_m, 0.0, 2e-6) << name << " " << R << " " << relief;
        EXPECT_LT(std::fabs(a.along_m), 5e-5) << name << " " << R << " " << relief;
        EXPECT_LT(a.speed, 1e-3) << name << " " << R << " " << relief;
      }
    }
    // Let down 1 mm off the top it rocks on the log, rolling (it would slip at 3 mm, friction 0.3),
    // and gains nothing.
    for (const bool relief : {false, true}) {
      const AcrossABulge r = lieAcross(false, 0.02, relief, kind, 0.001);
      std::printf("[measured] %s let down 1 mm off a 20 mm log's top (%s): highest %.2f um over R + r in its first half "
                  "second rocking, %.2f um in its fourth\n",
                  name, relief ? "flat relief" : "smooth chart", r.first_high_m * 1e6, r.last_high_m * 1e6);
      EXPECT_GT(r.first_high_m, 0.0) << name << " " << relief;  // it rocks
      EXPECT_LT(r.last_high_m, r.first_high_m + 0.05e-6) << name << " " << relief;
      EXPECT_LT(std::fabs(r.along_m), 2e-3) << name << " " << relief;
    }
    // On a sphere it may roll off sideways (unstable); its smooth chart is symmetric about it.
    const AcrossABulge s = lieAcross(true, 0.05, false, kind);
    std::printf("[measured] %s across a 5 cm sphere's top (smooth chart): axis %+.2f um from R + r\n", name, s.off_m * 1e6);
    EXPECT_NEAR(s.off_m, 0.0, 2e-6) << name;
  }
}

}  // namespace
}  // namespace thx::phys::test::test_plain_objects_on_relief_mesh
