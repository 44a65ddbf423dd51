// An object across a crease of a relief-textured mesh (chart_boundary.hpp): a 2 x 2 x 1 cm block
// resting on the grooved top of a slab (grooved_block_scene.hpp's flat mesh, V-grooves along y, a
// ridge on the slab's edge at x = 0.1 m), its centre 3 mm short of the edge or 3 mm past it. The
// chart under its centre is the top face or the side face; each runs on past the edge as a plane.
// Before the boundary, the block past the edge met the side face's plane run on up above the top,
// 7 mm deep, and was thrown off at 1.4 m/s; the block short of the edge crept (0.36 mm in 0.3 s); in a
// room (an inward box mesh) the floor's chart ran on under the wall and a block pushed into the
// wall went through it. The same slab and room untextured meet a block on the smooth chart
// (mesh_relief_chart.hpp), held to the same answers, and on Bullet's triangles (the baseline).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "tests/physics/grooved_block_scene.hpp"

namespace thx::phys::test::test_object_across_a_crease {
namespace {

using namespace grooved_block;

constexpr double kEdge = 0.1;  // the slab's edge (x), its top at z = 0

struct Tip {
  double pitch_30ms = 0.0, pitch_60ms = 0.0;  // rad, about the edge (y)
  double fastest_x = 0.0;                     // m/s, the centre's largest speed along x
  double fastest_late = 0.0;                  // m/s, its largest speed after 0.1 s
  double moved_m = 0.0;                       // the centre's travel over the run
};

// The grooved relief, the same mesh untextured met on its smooth chart, or on Bullet's triangles.
enum class Ground { Grooved, Smooth, Triangles };

MeshContactOptions untextured(Ground ground) {
  MeshContactOptions options;
  options.smooth_chart = ground == Ground::Smooth;
  return options;
}

// The block at rest on the ridges (its underside on z = 0), centre `beyond` past the edge, for
// `seconds`.
Tip release(double beyond, Ground ground, double seconds) {
  const mesh::GeneratedMesh slab = groovedGround(false);
  const tex::TextureMap map = heightMap(128, kExtent, vGrooves);
  PhysicsWorld world;
  if (ground == Ground::Grooved) {
    addGroovedGround(world, slab, false, map);
  } else {
    world.addTexturedMesh(slab.mesh, at(0.0, 0.0, -0.01), {1.0, 0.0, 0.0}, untextured(ground));
  }
  btRigidBody& block = world.addBox(kHalf, kMass, at(kEdge + beyond, 0.0, kHalf.z() + 1e-6), {kFriction, 0.0, 0.0});
  const Eigen::Vector3d start = positionOf(block);
  Tip tip;
  for (int k = 1; k <= int(std::lround(seconds / kDt)); ++k) {
    world.step(kDt);
    tip.fastest_x = std::max(tip.fastest_x, std::fabs(double(block.getLinearVelocity().x())));
    if (k > 100) tip.fastest_late = std::max(tip.fastest_late, double(block.getLinearVelocity().length()));
    btScalar yaw, pitch, roll;
    block.getWorldTransform().getBasis().getEulerZYX(yaw, pitch, roll);
    if (k == 30) tip.pitch_30ms = double(pitch);
    if (k == 60) tip.pitch_60ms = double(pitch);
  }
  tip.moved_m = (positionOf(block) - start).norm();
  return tip;
}

// The block pivoting from rest about the edge under its underside, without slipping: the pitch at
// time t (RK4 at 0.1 ms). Its centre lies d past the pivot and half its height h above it.
double pivotPitch(double d, double t) {
  const double a = kHalf.x(), h = kHalf.z(), r = std::hypot(d, h), phi0 = std::atan2(d, h);
  const double k = kG * r / ((a * a + h * h) / 3.0 + r * r);  // torque / inertia about the edge, per sin
  double theta = 0.0, omega = 0.0;
  const double dt = 1e-4;
  auto alpha = [&](double th) { return k * std::sin(phi0 + th); };
  for (int n = 0; n < int(std::lround(t / dt)); ++n) {
    const double k1t = omega, k1w = alpha(theta);
    const double k2t = omega + 0.5 * dt * k1w, k2w = alpha(theta + 0.5 * dt * k1t);
    const double k3t = omega + 0.5 * dt * k2w, k3w = alpha(theta + 0.5 * dt * k2t);
    const double k4t = omega + dt * k3w, k4w = alpha(theta + dt * k3t);
    theta += dt / 6.0 * (k1t + 2 * k2t + 2 * k3t + k4t);
    omega += dt / 6.0 * (k1w + 2 * k2w + 2 * k3w + k4w);
  }
  return theta;
}

TEST(ObjectAcrossACrease, ABlockShortOfTheEdgeStaysPut) {
  const Tip short_of = release(-0.003, Ground::Grooved, 0.3);
  const Tip smooth = release(-0.003, Ground::Smooth, 0.3);
  std::printf("[measured] centre 3 mm short of the edge: moved %.4f mm in 0.3 s, at most %.2g m/s along x, %.2g m/s "
              "after 0.1 s\n",
              short_of.moved_m * 1e3, short_of.fastest_x, short_of.fastest_late);
  std::printf("[measured] the same untextured, on its smooth chart: moved %.4f mm, %.2g m/s after 0.1 s\n",
              smooth.moved_m * 1e3, smooth.fastest_late);
  // Measured 6.5 um (settling onto the ridges) and 2.3e-5 m/s after 0.1 s; with the chart run on
  // past the edge, 0.36 mm and up to 13 mm/s.
  EXPECT_LT(short_of.moved_m, 2e-5);
  EXPECT_LT(short_of.fastest_late, 1e-4);
  EXPECT_LT(smooth.moved_m, 2e-5);
  EXPECT_LT(smooth.fastest_late, 1e-4);
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
  // Measured 0.182 and 0.770 rad against 0.199 and 0.837 untextured, 0.184 and 0.830 pivoting.
  EXPECT_NEAR(textured.pitch_30ms, plain.pitch_30ms, 0.15 * plain.pitch_30ms);
  EXPECT_NEAR(textured.pitch_60ms, plain.pitch_60ms, 0.15 * plain.pitch_60ms);
  EXPECT_NEAR(textured.pitch_30ms, pivot30, 0.15 * pivot30);
  EXPECT_NEAR(textured.pitch_60ms, pivot60, 0.15 * pivot60);
  // Not thrown: a block tipping off the edge moves at a fraction of a metre per second.
  EXPECT_LT(textured.fastest_x, 0.2);
  // The smooth chart's edge is the same crease: the same tipping. Before its chart dropped the
  // texels within a texel of the crease, the underside's edge sampled on the side face's chart
  // read 7 mm deep and the block was thrown back over the slab (-1.20 rad at 30 ms).
  EXPECT_NEAR(smooth.pitch_30ms, pivot30, 0.15 * pivot30);
  EXPECT_NEAR(smooth.pitch_60ms, pivot60, 0.15 * pivot60);
  EXPECT_LT(smooth.fastest_x, 0.2);
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
