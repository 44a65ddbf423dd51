// Two balls with bump maps, and a cylinder on one (box_ground.hpp): the larger ball's surface met as
// a relief mesh's (its cube-sphere, ObjectGround), the other object on the chart under it as on
// any relief mesh (relief_collision.hpp): for a ball with a bump map both reliefs in the pair's
// depth (Otaduy's directional depth), standing on the ground ball's bend. Before, these pairs met
// as coarse shapes. Checked against the exact contact, found by brute force over both balls'
// surfaces as textured_ball.hpp reads them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "clients/physics/box_ground.hpp"
#include "tests/physics/textured_ball_scene.hpp"

namespace thx::phys::test::test_textured_ball_pairs {
namespace {

using textured_ball::kRadius;  // both balls': 1 cm
using textured_ball::kTile;

using textured_ball::dimpleMap;

// The gap between ball A (centred at the origin, unturned) and ball B (centred at D u, turned by
// `b_turn`): the least over B's surface facing A of its height over A's surface, along A's radius.
double exactGap(const FaceTexture& a, const FaceTexture& b, const Eigen::Matrix3d& b_turn, const Eigen::Vector3d& u,
                double distance) {
  Eigen::Vector3d e1 = (std::fabs(u.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY()).cross(u).normalized();
  const Eigen::Vector3d e2 = u.cross(e1);
  double least = 1e9;
  constexpr int n = 120;
  constexpr double cone = 0.3;  // rad of B's surface round the line to A
  for (int i = -n; i <= n; ++i)
    for (int j = -n; j <= n; ++j) {
      const double x = cone * double(i) / n, y = cone * double(j) / n;
      if (x * x + y * y > cone * cone) continue;
      const Eigen::Vector3d w_world = Eigen::Vector3d(-u + x * e1 + y * e2).normalized();
      const Eigen::Vector3d w_b = b_turn.transpose() * w_world;
      const Eigen::Vector3d q = distance * u + (kRadius - ballTextureAt(b, kRadius, w_b).recess_m) * w_world;
      const double height = q.norm() - (kRadius - ballTextureAt(a, kRadius, q).recess_m);
      least = std::min(least, height);
    }
  return least;
}

// The centre distance at which the two touch (bisection on exactGap, to 0.01 um).
double exactTouch(const FaceTexture& a, const FaceTexture& b, const Eigen::Matrix3d& b_turn, const Eigen::Vector3d& u) {
  double lo = 2.0 * kRadius - 1e-3, hi = 2.0 * kRadius + 1e-4;
  while (hi - lo > 1e-8) {
    const double mid = 0.5 * (lo + hi);
    (exactGap(a, b, b_turn, u, mid) > 0.0 ? hi : lo) = mid;
  }
  return 0.5 * (lo + hi);
}

// Ball B let down on top of ball A (fixed) from 0.1 mm above where they touch, turned by `b_turn`
// and kept from turning further (its inertia made huge: only its height is asked here); B's
// centre height after 0.6 s.
double letDown(const FaceTexture* a, const FaceTexture* b, const Eigen::Matrix3d& b_turn, double touch, bool b_first) {
  PhysicsWorld world;
  const auto addA = [&] {
    if (a)
      world.addTexturedSphere(kRadius, 0.0, Eigen::Isometry3d::Identity(), {0.5, 0.0, 0.0}, *a);
    else
      world.addSphere(kRadius, 0.0, Eigen::Isometry3d::Identity(), {0.5, 0.0, 0.0});
  };
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = b_turn;
  pose.translation() = Eigen::Vector3d(0.0, 0.0, touch + 1e-4);
  btRigidBody* ball = nullptr;
  if (!b_first) addA();
  ball = b ? &world.addTexturedSphere(kRadius, 0.03, pose, {0.5, 0.0, 0.0}, *b)
           : &world.addSphere(kRadius, 0.03, pose, {0.5, 0.0, 0.0});
  if (b_first) addA();
  // Held on the line through A's centre: only the contact's height is measured.
  ball->setLinearFactor(btVector3(0, 0, 1));
  ball->setAngularFactor(btVector3(0, 0, 0));
  for (int k = 0; k < 600; ++k) world.step(1e-3);
  return positionOf(*ball).z();
}

// Each ball on the other, one uniformly recessed, the other dimpled: where the smaller sphere meets
// the dimpled ball's top (or bottom) dimple, the exact answer either way round and whichever shape
// is added first (the tie: the second is the ground). Then two bumpy balls: as laid they nest, 0.29
// mm nearer than the lower ball's bumps alone would let a smooth ball come; turned by a half period
// they do not.
TEST(TexturedBallPairs, TwoBallsWithBumpMapsTouchWhereTheirExactSurfacesDo) {
  const tex::TextureMap dimple_map = dimpleMap();
  const tex::TextureMap recess_map = textured_ball::uniformRecess(0.5e-3);
  const tex::TextureMap smooth_map = flatRelief(64);
  const FaceTexture dimpled = textured_ball::ballTexture(dimple_map), recessed = textured_ball::ballTexture(recess_map);
  const FaceTexture smooth = textured_ball::ballTexture(smooth_map);
  const Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
  const Eigen::Matrix3d unturned = Eigen::Matrix3d::Identity();
  struct Case {
    const char* name;
    const FaceTexture *a, *b;
    Eigen::Matrix3d turn;
    double tolerance;
  };
  // Bumps 0.3 mm high (textured_ball_scene.hpp): two such balls as laid nest (the exact touch
  // 0.29 mm nearer than the smooth ball's on the lower one's bumps); the upper turned by a half
  // period along both of its bottom face's axes, they do not.
  const tex::TextureMap bump_map = textured_ball::bumpMap(0.3e-3);
  const FaceTexture bumpy = textured_ball::ballTexture(bump_map);
  const double half_period = kTile / 8.0;
  const Eigen::Vector3d tip(std::tan(half_period / kRadius), std::tan(half_period / kRadius), -1.0);
  const Eigen::Matrix3d tip_down = Eigen::Quaterniond::FromTwoVectors(tip.normalized(), -Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Case cases[] = {
      {"recessed on recessed", &recessed, &recessed, unturned, 3e-6},
      {"recessed on dimpled", &dimpled, &recessed, unturned, 3e-6},
      {"dimpled on recessed", &recessed, &dimpled, unturned, 3e-6},
      {"bumpy on bumpy, as laid (they nest)", &bumpy, &bumpy, unturned, 15e-6},
      {"bumpy on bumpy, the upper turned a half period diagonally", &bumpy, &bumpy, tip_down, 3e-6},
  };
  for (const Case& c : cases) {
    const double touch = exactTouch(*c.a, *c.b, c.turn, up);
    const double upper_plain = exactTouch(*c.a, smooth, c.turn, up);
    for (const bool b_first : {false, true}) {
      const double z = letDown(c.a, c.b, c.turn, touch, b_first);
      std::printf("[measured] %s (%s added first): at rest %.2f um off the exact touch (%.4f mm); the upper ball's "
                  "texture unread, the exact touch %.4f mm\n",
                  c.name, b_first ? "upper" : "lower", (z - touch) * 1e6, touch * 1e3, upper_plain * 1e3);
      EXPECT_NEAR(z, touch, c.tolerance) << c.name;
      // Where both reliefs decide the touch, nearer it than to the answer with one of them.
      if (std::fabs(upper_plain - touch) > 10.0 * c.tolerance) {
        EXPECT_LT(std::fabs(z - touch), 0.1 * std::fabs(upper_plain - touch)) << c.name;
      }
    }
  }
}

// Two balls recessed 0.5 mm everywhere pressed together along lines through their centres that lie
// along a world axis, across a diagonal and off every axis: they rest where their recessed spheres
// touch, 2 (r - 0.5 mm) apart, whichever way the line runs.
TEST(TexturedBallPairs, PressedTogetherAlongAnyLineTheyRestWhereTheirSurfacesTouch) {
  const tex::TextureMap recess_map = textured_ball::uniformRecess(0.5e-3);
  const FaceTexture recessed = textured_ball::ballTexture(recess_map);
  const double touch = 2.0 * (kRadius - 0.5e-3);
  for (const Eigen::Vector3d& line : {Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(1, 1, 0), Eigen::Vector3d(1, 1, 1),
                                      Eigen::Vector3d(1, -2, 0.5), Eigen::Vector3d(-0.3, 0.8, 1)}) {
    const Eigen::Vector3d u = line.normalized();
    PhysicsWorld world;
    world.addTexturedSphere(kRadius, 0.0, Eigen::Isometry3d::Identity(), {0.5, 0.0, 0.0}, recessed);
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.translation() = (touch + 1e-4) * u;
    btRigidBody& ball = world.addTexturedSphere(kRadius, textured_ball::kMass, pose, {0.5, 0.0, 0.0}, recessed);
    const textured_ball::PressedRest rest = textured_ball::pressTowardsOrigin(world, ball, u);
    std::printf("[measured] recessed balls pressed along (%.2f, %.2f, %.2f): at rest %.2f um off the touch, %.2f um off the line at most\n",
                u.x(), u.y(), u.z(), (rest.distance_m - touch) * 1e6, rest.off_line_m * 1e6);
    EXPECT_NEAR(rest.distance_m, touch, 3e-6) << u.transpose();
    EXPECT_LT(rest.off_line_m, 1e-6) << u.transpose();
  }
}

// A cylinder lying across the top of a fixed ball recessed 0.5 mm everywhere rests on it at the
// smaller sphere's height, where the coarse pair put it on the full sphere.
TEST(TexturedBallPairs, ACylinderLyingOnABallWithABumpMapRestsOnItsRecessedSurface) {
  const tex::TextureMap recess_map = textured_ball::uniformRecess(0.5e-3);
  const FaceTexture recessed = textured_ball::ballTexture(recess_map);
  constexpr double r = 0.003, half = 0.01;
  for (const bool textured : {true, false}) {
    PhysicsWorld world;
    if (textured)
      world.addTexturedSphere(kRadius, 0.0, Eigen::Isometry3d::Identity(), {0.5, 0.0, 0.0}, recessed);
    else
      world.addSphere(kRadius, 0.0, Eigen::Isometry3d::Identity(), {0.5, 0.0, 0.0});
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.linear() = Eigen::AngleAxisd(0.5 * kPi, Eigen::Vector3d::UnitY()).toRotationMatrix();  // its axis along x
    pose.translation() = Eigen::Vector3d(0.0, 0.0, kRadius + r + 1e-4);
    btRigidBody& cylinder = world.addCylinder(r, half, 0.02, pose, {0.5, 0.0, 0.0});
    cylinder.setLinearFactor(btVector3(0, 0, 1));
    cylinder.setAngularFactor(btVector3(0, 0, 0));
    for (int k = 0; k < 600; ++k) world.step(1e-3);
    const double z = positionOf(cylinder).z(), expected = kRadius - (textured ? 0.5e-3 : 0.0) + r;
    std::printf("[measured] cylinder on the %s ball: at rest %.2f um off %.3f mm\n", textured ? "recessed" : "plain",
                (z - expected) * 1e6, expected * 1e3);
    EXPECT_NEAR(z, expected, 3e-6);
  }
}

// A ball that leaves the other's reach and comes back on its far side is met there. The pair's
// algorithm keeps the foot of the last step it was within reach (on the ground ball's -z face,
// where the small ball first touched it from below); Bullet keeps the pair while their bounds,
// each widened by 2 cm, meet. Until 2026-12-05 the walk started from that kept foot: against its
// face's plane the small ball, back above the ground ball, read as behind the winding, met
// nothing, and went into it (the pen of `bumpy_marbles_bowl` pushed one marble through another).
TEST(TexturedBallPairs, ABallThatLeftItsReachAndCameBackOnTheFarSideIsMetThere) {
  const tex::TextureMap map = textured_ball::bumpMap(1e-4);
  const FaceTexture bumps = textured_ball::ballTexture(map);
  constexpr double kBig = 0.008, kSmall = 0.006;
  WorldOptions options;
  options.gravity_m_per_s2 = Eigen::Vector3d::Zero();
  options.rest.enabled = false;
  PhysicsWorld world(options);
  world.addTexturedSphere(kBig, 0.0, Eigen::Isometry3d::Identity(), {0.5, 0.0, 0.0}, bumps);
  btRigidBody& ball = world.addTexturedSphere(kSmall, 0.007, at(0.0, 0.0, -(kBig + kSmall + 5e-4)), {0.5, 0.0, 0.0}, bumps);
  const auto moveTo = [&](const Eigen::Vector3d& p, const Eigen::Vector3d& v) {
    btTransform t = ball.getWorldTransform();
    t.setOrigin(toBt(p));
    ball.setWorldTransform(t);
    ball.setLinearVelocity(toBt(v));
    ball.setAngularVelocity(btVector3(0, 0, 0));
  };
  // Up against it from below: met there.
  moveTo(Eigen::Vector3d(0.0, 0.0, -(kBig + kSmall + 5e-4)), Eigen::Vector3d(0.0, 0.0, 0.01));
  for (int k = 0; k < 100; ++k) world.step(1e-3);
  const double below = positionOf(ball).norm();
  // Aside, beyond its reach (11 mm of gap) but within Bullet's 2 cm widened bounds, then above it
  // coming down.
  moveTo(Eigen::Vector3d(0.0, kBig + kSmall + 0.011, 0.0), Eigen::Vector3d::Zero());
  for (int k = 0; k < 20; ++k) world.step(1e-3);
  moveTo(Eigen::Vector3d(0.0, 0.0, kBig + kSmall + 5e-4), Eigen::Vector3d(0.0, 0.0, -0.01));
  double closest = 1.0;
  for (int k = 0; k < 200; ++k) {
    world.step(1e-3);
    closest = std::min(closest, positionOf(ball).norm());
  }
  std::printf("[measured] a bumpy ball met from below: centres %.3f mm apart; come back from above: %.3f mm at the "
              "closest (the radii's sum %.1f mm)\n",
              below * 1e3, closest * 1e3, (kBig + kSmall) * 1e3);
  EXPECT_GT(below, kBig + kSmall - 2.5e-4);  // the two bump layers' depth at most
  EXPECT_GT(closest, kBig + kSmall - 2.5e-4);
}

}  // namespace
}  // namespace thx::phys::test::test_textured_ball_pairs
