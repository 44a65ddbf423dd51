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

}  // namespace
}  // namespace thx::phys::test::test_plain_objects_on_relief_mesh
