// An object across a crease of a relief-textured mesh (chart_boundary.hpp): a 2 x 2 x 1 cm block
// resting on the grooved top of a slab (grooved_block_scene.hpp's flat mesh, V-grooves along y, a
// ridge on the slab's edge at x = 0.1 m), its centre 3 mm short of the edge or 3 mm past it. The
// chart under its centre is the top face or the side face; each runs on past the edge as a plane.
// Before the boundary, the block past the edge met the side face's plane run on up above the top,
// 7 mm deep, and was thrown off at 1.4 m/s; the block short of the edge crept (0.36 mm in 0.3 s); in a
// room (an inward box mesh) the floor's chart ran on under the wall and a block pushed into the
// wall went through it. The same slab and room untextured meet a block on the smooth chart
// (mesh_relief_chart.hpp), held to the same answers, and on Bullet's triangles (the baseline).
// A grooved block down in the slab's grooves by the edge meets the surface across the crease on
// that surface's own chart: when the faces across a crease were Bullet's flat triangles, at the
// relief's top, it read the grooves' depth as penetration there and was thrown back at 1.35 m/s.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "tests/physics/crease_scene.hpp"

namespace thx::phys::test::test_object_across_a_crease {
namespace {

using namespace crease;

TEST(ObjectAcrossACrease, ABlockShortOfTheEdgeStaysPut) {
  const Tip short_of = release(-0.003, Ground::Grooved, 0.3);
  const Tip smooth = release(-0.003, Ground::Smooth, 0.3);
  std::printf("[measured] centre 3 mm short of the edge: moved %.4f mm in 0.3 s, %.4f mm of it after 0.1 s\n",
              short_of.moved_m * 1e3, short_of.drift_m * 1e3);
  std::printf("[measured] the same untextured, on its smooth chart: moved %.4f mm, %.4f mm after 0.1 s\n",
              smooth.moved_m * 1e3, smooth.drift_m * 1e3);
  // Measured 48 um settling onto the ridges as the texels sample them (the ridge on the edge is
  // read 0.1 mm below its crest, the others up to 0.05 mm: the block tilts 0.008 rad towards the
  // edge and rests there), then 0.1 um; with the chart run on past the edge it crept 0.36 mm at up
  // to 13 mm/s.
  EXPECT_LT(short_of.moved_m, 1e-4);
  EXPECT_LT(short_of.drift_m, 2e-6);
  EXPECT_LT(smooth.moved_m, 2e-5);
  EXPECT_LT(smooth.drift_m, 2e-6);
}

TEST(ObjectAcrossACrease, ABlockPastTheEdgeTipsOverItAsOnTheUntexturedSlab) {
  const Tip textured = release(0.003, Ground::Grooved, 0.06);
  const Tip smooth = release(0.003, Ground::Smooth, 0.06);
  const Tip plain = release(0.003, Ground::Triangles, 0.06);
  const double pivot30 = pivotPitch(0.003, 0.03), pivot60 = pivotPitch(0.003, 0.06);
  std::printf("[measured] centre 3 mm past the edge: pitch %.3f rad at 30 ms, %.3f at 60 ms (untextured slab on its "
              "smooth chart %.3f, %.3f; on Bullet's triangles %.3f, %.3f; pivoting on the edge without slipping %.3f, "
              "%.3f); at most %.2f m/s along x (%.2f, %.2f)\n",
              textured.pitch_30ms, textured.pitch_60ms, smooth.pitch_30ms, smooth.pitch_60ms, plain.pitch_30ms,
              plain.pitch_60ms, pivot30, pivot60, textured.fastest_x, smooth.fastest_x, plain.fastest_x);
  // It turns about the edge as on Bullet's own triangles, and as the pivot does while it holds.
  // Measured 0.241 and 0.915 rad against 0.199 and 0.837 untextured, 0.184 and 0.830 pivoting.
  // All three lead the pivot early (the edge sinks 0.05-0.1 mm into its support as the weight comes
  // onto it); the grooved slab's the most, as the texels sample the ridge on the edge 63 um below
  // its crest: the block first turns on the crest 4 mm in, farther from its centre, then drops onto
  // the edge. By 60 ms each is within 10 % of the pivot.
  EXPECT_GT(textured.pitch_30ms, 0.5 * pivot30);  // tipping over the edge, not held or thrown back
  EXPECT_NEAR(textured.pitch_60ms, plain.pitch_60ms, 0.15 * plain.pitch_60ms);
  EXPECT_NEAR(textured.pitch_60ms, pivot60, 0.15 * pivot60);
  // Not thrown: a block tipping off the edge moves at a fraction of a metre per second.
  EXPECT_LT(textured.fastest_x, 0.2);
  // The smooth chart's edge is the same crease: the same tipping (0.215 and 0.870 rad). Before its
  // chart dropped the texels whose object points lie nearer the face across the crease, the
  // underside's edge sampled on the side face's chart read 7 mm deep and the block was thrown back
  // over the slab (-1.20 rad at 30 ms); before a refined point was kept on its chart, the block's
  // far edge over the air past the crease held it and it was thrown back too (-0.28 rad at 60 ms).
  EXPECT_NEAR(smooth.pitch_30ms, pivot30, 0.25 * pivot30);
  EXPECT_NEAR(smooth.pitch_60ms, pivot60, 0.15 * pivot60);
  EXPECT_LT(smooth.fastest_x, 0.2);
}

// The plain block far from the edge (no crease within reach), released level over a groove at
// four positions a texel apart in phase: it comes to rest on the crests. With the spread rule's
// points down the outer ridges' flanks it rested on one point a step and moved 0.2-3.1 mm in 0.9 s
// along the grooves (contact_selection.hpp, selectBoxQuarterContacts).
TEST(ObjectAcrossACrease, APlainBlockOnTheGroovedSlabComesToRest) {
  double most = 0.0;
  for (int k = 0; k < 4; ++k) {
    CreaseScene scene(-0.03 + k * 1e-4, Ground::Grooved, false);
    const Tip tip = scene.run(0.5);
    most = std::max(most, tip.drift_m);
  }
  std::printf("[measured] plain block on the grooved slab, far from its edge: moved at most %.2f um from 0.1 to 0.5 s\n",
              most * 1e6);
  // Measured 0.01 um (8.9 um while the row-by-row path took the spread rule); before the
  // quarter rule, 0.73 mm at the first position from 0.1 to 0.3 s.
  EXPECT_LT(most, 2e-5);
}

// The grooved block down in the slab's grooves, 2 mm short of the edge and 2 mm past it: the faces
// across the crease are met on their own chart, grooved as the texture lays them there.
TEST(ObjectAcrossACrease, AGroovedBlockDownInTheGroovesByTheEdgeMeetsTheFaceAcrossItsCrease) {
  const Tip short_of = release(-0.002, Ground::Grooved, 0.3, true);
  const Tip past = release(0.002, Ground::Grooved, 0.06, true);
  const double pivot60 = pivotPitch(0.002, 0.06);
  std::printf("[measured] grooved block in the grooves 2 mm short of the edge: moved %.4f mm in 0.3 s, %.4f mm after "
              "0.1 s; 2 mm past it: pitch %.3f rad at 30 ms, %.3f at 60 ms (a plain block pivoting on the edge %.3f at "
              "60 ms), at most %.2f m/s along x\n",
              short_of.moved_m * 1e3, short_of.drift_m * 1e3, past.pitch_30ms, past.pitch_60ms, pivot60, past.fastest_x);
  // Measured: short of the edge it drops the 0.2 mm it was released above its fit (0.15 mm) and
  // then holds (0.0 um); past it, 0.146 and 0.515 rad at 30 and 60 ms (it pivots on a ridge a
  // groove in from the edge), at most 0.16 m/s. When the faces across the crease were Bullet's
  // triangles at the relief's top (this test on the code before, 2026-12-02): short of the edge it
  // still moved 35 um from 0.1 to 0.3 s, past it it was thrown back over the slab (-0.80 rad at
  // 30 ms) at 1.35 m/s.
  EXPECT_LT(short_of.moved_m, 2.5e-4);
  EXPECT_LT(short_of.drift_m, 2e-6);
  EXPECT_GT(past.pitch_60ms, 0.3);  // it tips over the edge
  EXPECT_LT(past.fastest_x, 0.2);   // and is not thrown
}

// A capsule (3 mm radius, 2.6 cm long) lying down in a groove that runs off the slab's end (y = 0.1),
// its centre 4 mm short of the end or 2 mm past it. The end face is across the crease; the capsule
// overhangs it by 9 or 15 mm.
struct RodByTheEnd {
  Eigen::Vector3d moved_late = Eigen::Vector3d::Zero();  // from 0.05 s to the end
  Eigen::Vector3d moved = Eigen::Vector3d::Zero();
  double fastest = 0.0;  // m/s
};
RodByTheEnd rodByTheEnd(double beyond, double seconds) {
  const mesh::GeneratedMesh slab = groovedGround(false);
  const tex::TextureMap map = heightMap(128, kExtent, vGrooves);
  PhysicsWorld world;
  addGroovedGround(world, slab, false, map);
  const double radius = 0.003, wall = std::atan(2 * kDepth / kPeriod);
  // Along y, in the groove at x = 0.098, 0.2 mm above where it touches both walls.
  Eigen::Isometry3d pose = at(kEdge - 0.5 * kPeriod, 0.1 + beyond, radius / std::cos(wall) - kDepth + 2e-4);
  pose.linear() = Eigen::AngleAxisd(0.5 * kPi, Eigen::Vector3d::UnitX()).toRotationMatrix();
  btRigidBody& rod = world.addCapsule(radius, 0.01, 0.02, pose, {kFriction, 0.0, 0.0});
  const Eigen::Vector3d start = positionOf(rod);
  Eigen::Vector3d settled = start;
  RodByTheEnd out;
  for (int k = 1; k <= int(std::lround(seconds / kDt)); ++k) {
    world.step(kDt);
    out.fastest = std::max(out.fastest, double(rod.getLinearVelocity().length()));
    if (k == 50) settled = positionOf(rod);
  }
  out.moved = positionOf(rod) - start;
  out.moved_late = positionOf(rod) - settled;
  return out;
}

// The grooved block on the untextured slab's smooth chart, its centre over its own ridge 2 mm short
// of the edge: its ridges past the edge bear nothing, so it stands balanced on the outermost one
// that bears, in several manifolds (a textured box's groups by normal) whose normals agree to
// 1e-16. With their sticking points sharing their friction across the manifolds
// (contact_solver.hpp), it rocked off that ridge and tipped over the edge within 0.3 s (4.4 mm);
// split at each point without load, it crept 19 um from 0.1 to 0.3 s.
TEST(ObjectAcrossACrease, AGroovedBlockBalancedOnItsOutermostRidgeStaysOnTheSmoothChart) {
  const Tip balanced = release(-0.002, Ground::Smooth, 0.3, true);
  std::printf("[measured] grooved block on the untextured slab's smooth chart 2 mm short of the edge: moved %.4f mm "
              "in 0.3 s, %.4f mm after 0.1 s\n", balanced.moved_m * 1e3, balanced.drift_m * 1e3);
  // Measured 0.74 mm settling (released with its ridges 0.8 mm below the flat top, it rises onto
  // it), then 0.74 um.
  EXPECT_LT(balanced.moved_m, 1e-3);
  EXPECT_LT(balanced.drift_m, 5e-6);
}

TEST(ObjectAcrossACrease, ARodInAGrooveByTheSlabsEndRestsShortOfItAndTipsOverItPast) {
  const RodByTheEnd short_of = rodByTheEnd(-0.004, 0.3), past = rodByTheEnd(0.002, 0.1);
  std::printf("[measured] capsule in a groove 4 mm short of the slab's end: moved %.2f um from 0.05 to 0.3 s; 2 mm "
              "past it: moved (%.2f, %.2f, %.2f) mm in 0.1 s, at most %.2f m/s\n",
              short_of.moved_late.norm() * 1e6, past.moved.x() * 1e3, past.moved.y() * 1e3, past.moved.z() * 1e3,
              past.fastest);
  // Measured 0.00 um; past the end it tips over it (0.3, 3.9, -10.9 mm; 0.42 m/s at most). When the
  // end face was Bullet's triangles at the relief's top (the code before, 2026-12-02): short of the
  // end it was pushed 0.9 mm back along the groove, and past it thrown 35 mm along it at 0.96 m/s.
  EXPECT_LT(short_of.moved_late.norm(), 5e-6);
  EXPECT_LT(past.moved.z(), -3e-3);                    // tipping over the end
  EXPECT_LT(std::fabs(past.moved.y()), 1e-2);          // not thrown along the groove
  EXPECT_LT(past.fastest, 0.6);
}

// The floor of a 10 cm room (an inward box mesh) grooved like the slab, a block on it pushed
// towards a wall at half its weight: how far its face passes the wall.
double pushedIntoAWall(Ground ground) {
  const mesh::GeneratedMesh room = mesh::box({0.1, 0.1, 0.1}, 0.02, kExtent, true);
  const tex::TextureMap map = heightMap(128, kExtent, vGrooves);
  PhysicsWorld world;
  MeshContactOptions options;
  options.texture = &map;
  options.normals_made_for_m = Eigen::Vector2d::Constant(kExtent);
  // The floor at z = 0, the wall at x = 0.05.
  world.addTexturedMesh(room.mesh, at(0.0, 0.0, 0.05), {1.0, 0.0, 0.0},
                        ground == Ground::Grooved ? options : untextured(ground));
  btRigidBody& block = world.addBox(kHalf, kMass, at(0.05 - kHalf.x() - 0.002, 0.0, kHalf.z() + 1e-6), {kFriction, 0.0, 0.0});
  double deepest = -1.0;
  for (int k = 0; k < 400; ++k) {
    block.activate(true);
    block.applyCentralForce(btVector3(btScalar(0.5 * kMass * kG), 0, 0));
    world.step(kDt);
    deepest = std::max(deepest, positionOf(block).x() + kHalf.x() - 0.05);
  }
  return deepest;
}

TEST(ObjectAcrossACrease, ABlockPushedIntoAnInsideCornerIsHeldByTheWall) {
  const double textured = pushedIntoAWall(Ground::Grooved), smooth = pushedIntoAWall(Ground::Smooth),
               plain = pushedIntoAWall(Ground::Triangles);
  std::printf("[measured] a block pushed into the wall at half its weight: its face at most %+.3f mm past the wall "
              "(untextured room on its smooth chart %+.3f mm, on Bullet's triangles %+.3f mm)\n",
              textured * 1e3, smooth * 1e3, plain * 1e3);
  // Measured +0.062 mm (untextured +0.054 mm); without the boundary +272 mm: through the wall.
  EXPECT_LT(textured, 5e-4);
  EXPECT_LT(smooth, 5e-4);
}

}  // namespace
}  // namespace thx::phys::test::test_object_across_a_crease
