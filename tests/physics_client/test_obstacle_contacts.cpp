// Fixed obstacles stop what runs into them at their surface, for every pair of scene shapes:
// ball against capsule rails and bumpers, box walls and cylinder bumpers; block against box posts
// and cylinder posts. Run through the physics client's core on a flat normal-mapped plane.
//
// Ball-box, ball-cylinder and block-cylinder go through ScaledConvexAlgorithm
// (clients/physics/scaled_convex_collision.hpp): with Bullet's own convex-convex algorithm the
// ball sank 2.0 mm into the box wall and 0.49 mm into the cylinder bumper (docs/physics.md,
// "Shape pairs").
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "clients/physics_client/driver.hpp"
#include "clients/physics_client/physics_scene.hpp"
#include "scenes/scene_loader.hpp"

namespace test_obstacle_contacts {

namespace {

using namespace thx::physclient;

// A flat normal map (tilted by 0°), level: nothing but the obstacle acts on the object sideways.
const std::string kHead = R"(version: 1
name: obstacle
surface:
  size: [0.2, 0.2]
  texture: {generator: tilted, size: 64, params: {extent: 0.2, angle_deg: 0}}
  representation: normal
  material: wood
objects:
)";

class NullSink final : public EventSink {};

// Steps the scene for `seconds`; returns the deepest penetration of object 0 into the obstacle,
// measured by `depth(state)` (> 0: inside), and the object's last state.
template <class Depth>
double deepest(const std::string& objects, double seconds, Depth depth, BodyState* last = nullptr) {
  const thx::scene::Scene scene = thx::scene::parseScene(kHead + objects, "obstacle.yaml", ".");
  PhysicsScene sim(scene, SimOptions{});
  NullSink sink;
  Driver driver(sim, sink, DriverOptions{});
  double worst = -1.0;
  for (int k = 0; k < int(std::lround(seconds * 1000)); ++k) {
    driver.step(std::nullopt);
    worst = std::max(worst, depth(sim.body(0)));
  }
  if (last) *last = sim.body(0);
  return worst;
}

// A 2 × 2 × 1 cm block's deepest surface point inside an obstacle given as a point-depth function.
// The 2646 surface points are placed in plain doubles, not Eigen expressions: this runs every step,
// and the sanitizer tree builds test files at -O0, where the expressions made each test take about
// 4 s instead of 0.05 s (docs/build.md).
template <class Inside>
double blockDepth(const BodyState& b, Inside inside) {
  const Eigen::Matrix3d r = b.q_world.toRotationMatrix();
  const double* m = r.data();  // column-major
  const double* c = b.p_world.data();
  const double half[3] = {0.01, 0.01, 0.005};
  double worst = -1.0;
  for (int face = 0; face < 6; ++face)
    for (int i = 0; i <= 20; ++i)
      for (int j = 0; j <= 20; ++j) {
        double u[3];
        const int axis = face / 2;
        u[axis] = face % 2 ? 1.0 : -1.0;
        u[(axis + 1) % 3] = -1.0 + i / 10.0;
        u[(axis + 2) % 3] = -1.0 + j / 10.0;
        for (int k = 0; k < 3; ++k) u[k] *= half[k];
        const Eigen::Vector3d p(c[0] + m[0] * u[0] + m[3] * u[1] + m[6] * u[2],
                                c[1] + m[1] * u[0] + m[4] * u[1] + m[7] * u[2],
                                c[2] + m[2] * u[0] + m[5] * u[1] + m[8] * u[2]);
        worst = std::max(worst, inside(p));
      }
  return worst;
}

// Ball: r = 8 mm steel, rolling at 0.2 m/s along +x towards x = 0, its centre 8 mm up.
const std::string kBall =
    "  - {name: ball, shape: sphere, radius: 0.008, mass: 0.0168, material: steel, position: [-0.03, 0, 0.0081], "
    "velocity: [0.2, 0, 0], angular_velocity: [0, 25, 0]}\n";
// Block: 2 × 2 × 1 cm wood sliding at 0.5 m/s along +x; the post at x = 0 meets its front 3 mm
// from a corner (y offset 8 mm), as in letter_blocks.yaml.
const std::string kBlock =
    "  - {name: block, shape: box, size: [0.02, 0.02, 0.01], mass: 0.003, material: wood, position: [-0.03, -0.008, "
    "0.0052], velocity: [0.5, 0, 0]}\n";

TEST(PhysicsClientObstacle, BallStopsAtACapsuleRail) {
  BodyState end;
  const double pen = deepest(kBall + "  - {name: rail, shape: capsule, radius: 0.0025, length: 0.1, fixed: true, "
                                     "position: [0, 0, 0.008], rpy_deg: [-90, 0, 0]}\n",
                             0.5, [](const BodyState& b) { return 0.008 + 0.0025 - std::fabs(b.p_world.x()); }, &end);
  std::printf("[measured] ball into a capsule rail: deepest %.3f mm, ends at x = %.2f mm\n", pen * 1e3, end.p_world.x() * 1e3);
  EXPECT_LT(pen, 0.3e-3);
  EXPECT_LT(end.p_world.x(), -0.0105 + 0.3e-3);
}

// Hit 0-15 mm off centre (at 16 mm the ball misses), deepest over all.
template <class Bumper>
double ballIntoBumper(Bumper bumper) {
  double worst = -1.0;
  for (int k = 0; k <= 15; ++k) {
    const double off = 0.001 * k;
    worst = std::max(worst, deepest(kBall + bumper(off), 0.3, [off](const BodyState& b) {
                       return 0.016 - std::hypot(b.p_world.x(), b.p_world.y() - off);
                     }));
  }
  return worst;
}

std::string standing(const char* shape, double off) {
  char line[160];
  std::snprintf(line, sizeof line, "  - {name: bumper, shape: %s, radius: 0.008, length: 0.016, fixed: true, position: [0, %g, 0.008]}\n",
                shape, off);
  return line;
}

TEST(PhysicsClientObstacle, BallStopsAtAStandingCapsuleBumper) {
  const double pen = ballIntoBumper([](double off) { return standing("capsule", off); });
  std::printf("[measured] ball into a capsule bumper, 0-15 mm off centre: deepest %.3f mm\n", pen * 1e3);
  EXPECT_LT(pen, 0.3e-3);
}

TEST(PhysicsClientObstacle, BlockStopsAtABoxPost) {
  const double pen = deepest(kBlock + "  - {name: post, shape: box, size: [0.01, 0.01, 0.02], fixed: true, "
                                      "position: [0, 0, 0.01], rpy_deg: [0, 0, 45]}\n",
                             0.3, [](const BodyState& b) {
                               return blockDepth(b, [](const Eigen::Vector3d& p) {
                                 const double c = std::sqrt(0.5);  // the post turned 45° about z
                                 const double u = c * (p.x() + p.y()), v = c * (p.y() - p.x());
                                 return std::min({0.005 - std::fabs(u), 0.005 - std::fabs(v), 0.01 - std::fabs(p.z() - 0.01)});
                               });
                             });
  std::printf("[measured] block into a square post: deepest %.3f mm\n", pen * 1e3);
  EXPECT_LT(pen, 0.6e-3);  // box edges carry a 0.5 mm margin rounding
}

TEST(PhysicsClientObstacle, BallStopsAtABoxWall) {
  const double pen = deepest(kBall + "  - {name: wall, shape: box, size: [0.005, 0.1, 0.016], fixed: true, "
                                     "position: [0, 0, 0.008]}\n",
                             0.5, [](const BodyState& b) { return b.p_world.x() + 0.008 + 0.0025; });
  std::printf("[measured] ball into a box wall: deepest %.3f mm\n", pen * 1e3);  // 2.0 mm with Bullet's GJK alone
  EXPECT_LT(pen, 0.3e-3);
}

TEST(PhysicsClientObstacle, BallStopsAtACylinderBumper) {
  const double pen = ballIntoBumper([](double off) { return standing("cylinder", off); });
  std::printf("[measured] ball into a cylinder bumper, 0-15 mm off centre: deepest %.3f mm\n", pen * 1e3);  // 0.49 mm before
  EXPECT_LT(pen, 0.3e-3);
}

// The block of BlockStopsAtABoxPost against a round post (r 5 mm, 2 cm tall): with Bullet's own
// GJK a block sank 4.8 mm into such a post and was thrown off at 2.5x its speed.
TEST(PhysicsClientObstacle, BlockStopsAtACylinderPost) {
  BodyState end;
  const double pen = deepest(kBlock + "  - {name: post, shape: cylinder, radius: 0.005, length: 0.02, fixed: true, "
                                      "position: [0, 0, 0.01]}\n",
                             0.3, [](const BodyState& b) {
                               return blockDepth(b, [](const Eigen::Vector3d& p) {
                                 return std::min(0.005 - std::hypot(p.x(), p.y()), 0.01 - std::fabs(p.z() - 0.01));
                               });
                             }, &end);
  std::printf("[measured] block into a cylinder post: deepest %.3f mm, end speed %.3f m/s\n", pen * 1e3, end.v_world.norm());
  EXPECT_LT(pen, 0.3e-3);
  EXPECT_LT(end.v_world.norm(), 0.5);  // not thrown off faster than it came
}

}  // namespace

}  // namespace test_obstacle_contacts
