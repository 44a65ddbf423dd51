// A plain ball or a capsule against a ball with a bump map (ball_on_object_faces.hpp): the
// textured ball's surface met as a relief mesh's (its cube-sphere), the ball lifted onto its relief
// on the sphere's curvature (MeshContactOptions::sphere_radius_m). Checked against the exact
// contact, found by brute force over the textured ball's surface as textured_ball.hpp reads it
// (ballTextureAt: the recess along the radius at every direction). Before, such pairs met the
// coarse ball.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "clients/physics/ball_on_object_faces.hpp"
#include "tests/physics/textured_ball_scene.hpp"

namespace thx::phys::test::test_ball_on_textured_ball {
namespace {

using textured_ball::kRadius;  // the textured ball's: 1 cm
using textured_ball::kTile;

using textured_ball::dimpleMap;
constexpr double kRim = textured_ball::kDimpleRim, kDepth = textured_ball::kDimpleDepth;
const double kPitch = textured_ball::kDimplePitch;


// The textured ball's surface point in direction w (unit), as textured_ball.hpp reads it.
Eigen::Vector3d surfaceAt(const FaceTexture& texture, const Eigen::Vector3d& w) {
  return (kRadius - ballTextureAt(texture, kRadius, w).recess_m) * w;
}

// An orthonormal frame (e1, e2) across unit u.
void across(const Eigen::Vector3d& u, Eigen::Vector3d& e1, Eigen::Vector3d& e2) {
  e1 = (std::fabs(u.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY()).cross(u).normalized();
  e2 = u.cross(e1);
}

// The largest of f(w) over the directions w within `cone` of u: a grid, then a finer grid round
// its best (f is smooth between texels; the second grid is a fiftieth of a texel on the ball).
template <class F>
double maxOverDirections(const Eigen::Vector3d& u, double cone, F f) {
  Eigen::Vector3d e1, e2;
  across(u, e1, e2);
  double best = -1e9, bx = 0.0, by = 0.0;
  const auto scan = [&](double cx, double cy, double half, int n) {
    for (int i = -n; i <= n; ++i)
      for (int j = -n; j <= n; ++j) {
        const double x = cx + half * double(i) / double(n), y = cy + half * double(j) / double(n);
        if (x * x + y * y > cone * cone) continue;
        const double value = f(Eigen::Vector3d(u + x * e1 + y * e2).normalized());
        if (value > best) best = value, bx = x, by = y;
      }
  };
  scan(0.0, 0.0, cone, 150);
  const double coarse = cone / 150.0;
  scan(bx, by, 2.0 * coarse, 40);
  return best;
}

// How far from the textured ball's centre a ball of radius r centred on the line along u stands
// when it touches the surface: the largest over the surface's points of the distance along u at
// which the ball's sphere passes through them.
double exactCentreDistance(const FaceTexture& texture, const Eigen::Vector3d& u, double r) {
  return maxOverDirections(u, std::asin(std::min(1.0, r / (kRadius - kDepth))) + 0.02, [&](const Eigen::Vector3d& w) {
    const Eigen::Vector3d p = surfaceAt(texture, w);
    const double along = p.dot(u), off2 = (p - along * u).squaredNorm();
    return off2 < r * r ? along + std::sqrt(r * r - off2) : -1e9;
  });
}

// The triangle of the cube-sphere nearest direction u.
std::uint32_t triangleNear(const mesh::TexturedMesh& m, const Eigen::Vector3d& u) {
  std::uint32_t best = 0;
  double best_dot = -2.0;
  for (std::uint32_t t = 0; t < std::uint32_t(m.triangles.size()); ++t) {
    const auto& c = m.triangles[t];
    const double d = (m.positions[c[0]] + m.positions[c[1]] + m.positions[c[2]]).normalized().dot(u);
    if (d > best_dot) best_dot = d, best = t;
  }
  return best;
}

FaceTexture ballTextureOfMap(const tex::TextureMap& map) { return textured_ball::ballTexture(map); }

// A uniformly recessed ball is the smooth ball of radius R - depth: the cube-sphere's Phong surface,
// on which the lift is read, stands for it within a fraction of a micrometre.
TEST(BallOnTexturedBall, AUniformlyRecessedBallIsMetAsTheSmallerSphere) {
  const double depth = 0.5e-3;
  const tex::TextureMap map = textured_ball::uniformRecess(depth);
  const FaceTexture texture = ballTextureOfMap(map);
  const std::unique_ptr<ObjectFaces> faces = ballFaces(kRadius, texture);
  std::mt19937 random(7);
  std::normal_distribution<double> normal;
  double worst = 0.0;
  for (const double r : {0.002, 0.004, 0.006}) {
    for (int k = 0; k < 300; ++k) {
      const Eigen::Vector3d u = Eigen::Vector3d(normal(random), normal(random), normal(random)).normalized();
      const double expected_gap = 1e-4 * double(k % 5) - 1e-4;  // -0.1 .. 0.3 mm
      const Eigen::Vector3d c = (kRadius - depth + r + expected_gap) * u;
      const double gap = ballLiftedGap(faces->contact, c, triangleNear(faces->mesh, u), r, faces->options);
      worst = std::max(worst, std::fabs(gap - expected_gap));
    }
  }
  std::printf("[measured] 900 balls of 2, 4 and 6 mm round a 1 cm ball recessed 0.5 mm: gap off the smaller sphere's by %.3f um at most\n",
              worst * 1e6);
  EXPECT_LT(worst, 1e-6);
}

// Balls over the dimpled ball's top dimple, its rim and between dimples, and at random directions:
// the centre's distance from the textured ball's centre at touch, as the lifted ball reads it
// (ballLiftedGap), against the exact contact. Read on the tangent plane at the foot instead (no
// sphere_radius_m), the texels a distance d from the foot stand d^2 / 2R too high.
TEST(BallOnTexturedBall, ABallTouchesTheDimpledBallWhereTheExactContactDoes) {
  const tex::TextureMap map = dimpleMap();
  const FaceTexture texture = ballTextureOfMap(map);
  const std::unique_ptr<ObjectFaces> faces = ballFaces(kRadius, texture);
  MeshContactOptions flat = faces->options;
  flat.sphere_radius_m = 0.0;
  std::vector<Eigen::Vector3d> directions;
  const auto onTopFace = [](double u_m, double v_m) {  // the +z face's chart (textured_ball_mesh.hpp)
    return Eigen::Vector3d(std::tan(u_m / kRadius), std::tan(v_m / kRadius), 1.0).normalized();
  };
  directions.push_back(onTopFace(0.0, 0.0));                        // a dimple's centre
  directions.push_back(onTopFace(0.8e-3, 0.0));                     // its wall
  directions.push_back(onTopFace(kRim, 0.0));                       // its rim
  directions.push_back(onTopFace(0.5 * kPitch, 0.5 * kPitch));      // between four dimples
  directions.push_back(onTopFace(0.5 * kPitch, 0.0));               // between two
  std::mt19937 random(11);
  std::normal_distribution<double> normal;
  for (int k = 0; k < 6; ++k) directions.push_back(Eigen::Vector3d(normal(random), normal(random), normal(random)).normalized());
  for (const double r : {0.002, 0.004, 0.006}) {
    double worst = 0.0, worst_flat = 0.0;
    for (const Eigen::Vector3d& u : directions) {
      const double exact = exactCentreDistance(texture, u, r);
      const std::uint32_t t = triangleNear(faces->mesh, u);
      // The gap at the exact touch is the error of the distance read (the gap is linear along u).
      worst = std::max(worst, std::fabs(ballLiftedGap(faces->contact, exact * u, t, r, faces->options)));
      worst_flat = std::max(worst_flat, std::fabs(ballLiftedGap(faces->contact, exact * u, t, r, flat)));
    }
    std::printf("[measured] a %.0f mm ball at %zu places on the dimpled ball: off the exact touch by %.2f um at most "
                "(on the tangent plane: %.2f um)\n",
                r * 1e3, directions.size(), worst * 1e6, worst_flat * 1e6);
    // Measured: 0.79, 2.73 and 5.40 um. The 6 mm ball read 3.63 um until 2026-12-06, its foot
    // (smoothFoot) four undamped rounds short of where they lead (h / R about 0.6 there); walked
    // there, by sixty undamped rounds or by the damped walk, it reads 5.40 um: the lift's own error.
    EXPECT_LT(worst, 6e-6);
    EXPECT_GT(worst_flat, 2.5 * worst);
  }
}

// A marble let down 0.4 mm off the top dimple of a fixed dimpled ball stays in the dimple and swings
// in it (nothing damps a ball rolling without slipping) as the exact contact's geometry says: its
// centre on the curve the exact touch traces (found by brute force at the swing's ends and at the
// bottom), the period of a ball rolling on that curve, 2 pi sqrt(7 rho / 5 g) for the curve's
// radius rho (the dimple's floor, its cap on the ball's curve, is concave with a radius of about
// 11 mm, wider than the marble). On a plain ball of the same size it rolls off.
TEST(BallOnTexturedBall, AMarbleSwingsInADimpleOnTopOfADimpledBall) {
  const tex::TextureMap map = dimpleMap();
  const FaceTexture texture = ballTextureOfMap(map);
  constexpr double r = 0.003, m = 0.3e-3, dt = 1e-3, x0 = 0.4e-3;
  // The exact centre at the bottom and at the swing's ends (along x, a line of symmetry).
  const double bottom = exactCentreDistance(texture, Eigen::Vector3d::UnitZ(), r);
  const double phi = x0 / bottom;
  const double end = exactCentreDistance(texture, Eigen::Vector3d(std::sin(phi), 0.0, std::cos(phi)), r);
  const double x_end = end * std::sin(phi), rise = end * std::cos(phi) - bottom;
  const double rho = x_end * x_end / (2.0 * rise);
  const double predicted = 2.0 * kPi * std::sqrt(7.0 * rho / (5.0 * kG));
  for (const bool textured : {true, false}) {
    PhysicsWorld world;
    if (textured)
      world.addTexturedSphere(kRadius, 0.0, Eigen::Isometry3d::Identity(), {0.5, 0.0, 0.0}, texture);
    else
      world.addSphere(kRadius, 0.0, Eigen::Isometry3d::Identity(), {0.5, 0.0, 0.0});
    btRigidBody& marble = world.addSphere(r, m, at(x_end, 0.0, bottom + rise), {0.5, 0.0, 0.0});
    std::vector<double> crossings;  // upward zero crossings of x
    double previous = x_end, widest_late = 0.0, lowest = 1.0, farthest = 0.0;
    constexpr int steps = 2000;
    for (int k = 1; k <= steps; ++k) {
      world.step(dt);
      const Eigen::Vector3d p = positionOf(marble);
      if (previous < 0.0 && p.x() >= 0.0) crossings.push_back((double(k) - p.x() / (p.x() - previous)) * dt);
      previous = p.x();
      lowest = std::min(lowest, p.z());
      farthest = std::max(farthest, p.head<2>().norm());
      if (k > steps - 250) widest_late = std::max(widest_late, std::fabs(p.x()));
    }
    if (!textured) {
      std::printf("[measured] plain ball: the marble after 2 s at z = %.1f mm\n", positionOf(marble).z() * 1e3);
      EXPECT_LT(positionOf(marble).z(), kRadius);  // rolled off
      continue;
    }
    ASSERT_GE(crossings.size(), 3u);
    const double period = (crossings.back() - crossings.front()) / double(crossings.size() - 1);
    std::printf("[measured] dimpled ball: the marble swings with period %.2f ms (the exact curve's rolling period "
                "%.2f ms, its radius %.2f mm), %.3f mm wide in the last quarter second of 2 s (from %.3f), at most "
                "%.3f mm off the dimple's axis, lowest %.2f um off the exact bottom\n",
                period * 1e3, predicted * 1e3, rho * 1e3, widest_late * 1e3, x_end * 1e3, farthest * 1e3,
                (lowest - bottom) * 1e6);
    EXPECT_NEAR(period, predicted, 0.02 * predicted);
    EXPECT_GT(widest_late, 0.9 * x_end);
    EXPECT_LT(farthest, 1.1 * x_end);
    EXPECT_NEAR(lowest, bottom, 3e-6);
  }
}

// A capsule lying over the dimpled ball (4 mm, the pen's radius): the least gap of its points after
// collision detection against the exact distance from its segment to the textured surface.
TEST(BallOnTexturedBall, ACapsuleOverTheDimpledBallMeetsItWhereTheExactContactDoes) {
  const tex::TextureMap map = dimpleMap();
  const FaceTexture texture = ballTextureOfMap(map);
  constexpr double r = 0.004, half = 0.006;
  std::mt19937 random(5);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const std::unique_ptr<ObjectFaces> faces = ballFaces(kRadius, texture);  // as the world's
  double worst = 0.0;
  int met = 0;
  for (int k = 0; k < 12; ++k) {
    // Its axis level over the top, shifted and turned, -0.05 to 0.1 mm clear of the smooth ball.
    const double yaw = kPi * unit(random), shift = 2e-3 * unit(random), along = 4e-3 * unit(random);
    const Eigen::Vector3d axis(std::cos(yaw), std::sin(yaw), 0.0);
    const Eigen::Vector3d side(-axis.y(), axis.x(), 0.0);
    const Eigen::Vector3d centre = along * axis + shift * side +
                                   Eigen::Vector3d(0.0, 0.0, std::sqrt(std::pow(kRadius + r, 2) - shift * shift) + 0.25e-4 + 0.75e-4 * unit(random));
    const Eigen::Vector3d a = centre - half * axis, b = centre + half * axis;
    // Exact: the least distance from the segment to the surface, less r.
    const double exact = -maxOverDirections(centre.normalized(), 0.9, [&](const Eigen::Vector3d& w) {
                           const Eigen::Vector3d p = surfaceAt(texture, w);
                           const double s = std::clamp((p - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
                           return -(p - (a + s * (b - a))).norm();
                         }) - r;
    PhysicsWorld world;
    world.addTexturedSphere(kRadius, 0.0, Eigen::Isometry3d::Identity(), {0.5, 0.0, 0.0}, texture);
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.translation() = centre;
    pose.linear() = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), axis).toRotationMatrix();
    const btRigidBody& capsule = world.addCapsule(r, half, 0.01, pose, {0.5, 0.0, 0.0});  // a body: two fixed objects are never paired
    world.world().performDiscreteCollisionDetection();
    // Each point's ball (ballCentreOfPoint), its lifted gap read as the rewrite reads it (the
    // point's own distance is the one the solver holds on the flat triangle).
    btDispatcher& dispatcher = *world.world().getDispatcher();
    double least = 1e9;
    for (int i = 0; i < dispatcher.getNumManifolds(); ++i) {
      const btPersistentManifold* manifold = dispatcher.getManifoldByIndexInternal(i);
      for (int j = 0; j < manifold->getNumContacts(); ++j) {
        const btManifoldPoint& point = manifold->getContactPoint(j);
        const Eigen::Vector3d ball = pose * ballCentreOfPoint(point, *capsule.getCollisionShape());
        least = std::min(least, ballLiftedGap(faces->contact, ball, std::uint32_t(point.m_index1), r, faces->options));
      }
    }
    if (least > 1.0) continue;
    ++met;
    worst = std::max(worst, std::fabs(least - exact));
  }
  std::printf("[measured] a 4 mm capsule over the dimpled ball in %d of 12 poses: its least gap off the exact one by %.2f um at most\n",
              met, worst * 1e6);
  EXPECT_EQ(met, 12);
  EXPECT_LT(worst, 5e-6);
}

}  // namespace
}  // namespace thx::phys::test::test_ball_on_textured_ball
