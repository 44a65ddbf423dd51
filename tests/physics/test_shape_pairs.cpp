// Every pair of convex scene shapes reports its overlap and normal as the geometry says: random
// poses with overlaps of 0.05-2 mm, depth and normal against the analytic answer.
//
// Bullet's boxes and cylinders carry a collision margin (0.5 mm here) and are the Minkowski sum
// of a core shrunk by the margin and a ball of that radius: faces and sides are where the scene
// puts them, edges and rims are rounded with the margin's radius. The analytic answer is that of
// the rounded shape: the overlap of two shapes with cores K1, K2 and margins m1, m2 is
// m1 + m2 - dist(K1, K2) (a sphere's core is its centre, a capsule's its segment).
//
// Before ScaledConvexAlgorithm (WorldOptions::scaled_convex_pairs = false: Bullet's own
// btConvexConvexAlgorithm) the same cases missed most overlaps; the test prints both.
#include <gtest/gtest.h>

#include <BulletCollision/CollisionDispatch/btSphereBoxCollisionAlgorithm.h>
#include <BulletCollision/NarrowPhaseCollision/btPersistentManifold.h>

#include <algorithm>
#include <cstdio>
#include <functional>
#include <optional>
#include <random>

#include "clients/physics/bullet_convert.hpp"
#include "physics_fixtures.hpp"

namespace thx::phys::test::test_shape_pairs {
namespace {

constexpr double kMargin = 0.5e-3;

// Deterministic on every platform: the raw engine's output, not a std distribution.
struct Random {
  std::mt19937 engine{20261125u};
  double uniform(double lo, double hi) { return lo + (hi - lo) * (double(engine()) / 4294967296.0); }
  Eigen::Quaterniond rotation() {
    Eigen::Quaterniond q(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1), uniform(-1, 1));
    return q.norm() > 1e-3 ? q.normalized() : Eigen::Quaterniond::Identity();
  }
  Eigen::Vector3d unit() { return rotation() * Eigen::Vector3d::UnitX(); }
};

// One posed pair and what the geometry says: overlap depth (m, > 0) and the normal pointing from
// `second` to `first`.
struct PairCase {
  Eigen::Isometry3d first = Eigen::Isometry3d::Identity(), second = Eigen::Isometry3d::Identity();
  double depth = 0.0;
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
};

struct Shape {
  std::function<btRigidBody&(PhysicsWorld&, const Eigen::Isometry3d&)> add;
  double margin = 0.0;  // GJK's margin: a sphere's or capsule's radius, kMargin otherwise
};

Shape sphere(double r) {
  return {[r](PhysicsWorld& w, const Eigen::Isometry3d& p) -> btRigidBody& { return w.addSphere(r, 0.01, p, {}); }, r};
}
Shape box(const Eigen::Vector3d& half) {
  return {[half](PhysicsWorld& w, const Eigen::Isometry3d& p) -> btRigidBody& { return w.addBox(half, 0.01, p, {}); },
          kMargin};
}
Shape cylinder(double r, double half_length) {
  return {[=](PhysicsWorld& w, const Eigen::Isometry3d& p) -> btRigidBody& {
            return w.addCylinder(r, half_length, 0.01, p, {});
          },
          kMargin};
}
Shape capsule(double r, double half_length) {
  return {[=](PhysicsWorld& w, const Eigen::Isometry3d& p) -> btRigidBody& {
            return w.addCapsule(r, half_length, 0.01, p, {});
          },
          r};
}

// Worst errors apart for the two regimes of Bullet's GJK: overlaps smaller than the sum of the
// two margins leave the cores apart and GJK measures their distance; deeper ones make the cores
// overlap and EPA measures the penetration (only box-cylinder and cylinder-cylinder reach it
// here: a sphere's or capsule's margin is its radius).
struct Stats {
  int cases = 0, missed = 0, core_overlaps = 0;
  double worst_depth_error = 0.0, worst_angle_deg = 0.0;         // cores apart (GJK)
  double worst_depth_error_epa = 0.0, worst_angle_deg_epa = 0.0;  // cores overlapping (EPA)
};

enum class Engine { Scaled, BulletConvexConvex, BulletSphereBox };

// Poses both shapes as each case says and runs the world's collision detection on them alone.
Stats measure(const Shape& a, const Shape& b, const std::vector<PairCase>& cases, Engine engine) {
  const double margins = a.margin + b.margin;
  WorldOptions options;
  options.gravity_m_per_s2.setZero();
  options.scaled_convex_pairs = engine == Engine::Scaled;
  PhysicsWorld w(options);
  if (engine == Engine::BulletSphereBox) {  // the algorithm btDefaultCollisionConfiguration leaves out
    static btSphereBoxCollisionAlgorithm::CreateFunc direct, swapped;
    swapped.m_swapped = true;
    auto& dispatcher = static_cast<btCollisionDispatcher&>(*w.world().getDispatcher());
    dispatcher.registerCollisionCreateFunc(SPHERE_SHAPE_PROXYTYPE, BOX_SHAPE_PROXYTYPE, &direct);
    dispatcher.registerCollisionCreateFunc(BOX_SHAPE_PROXYTYPE, SPHERE_SHAPE_PROXYTYPE, &swapped);
  }
  btRigidBody& first = a.add(w, Eigen::Isometry3d::Identity());
  btRigidBody& second = b.add(w, at(0.5, 0, 0));
  Stats s;
  for (const PairCase& c : cases) {
    first.setWorldTransform(toBt(c.first));
    second.setWorldTransform(toBt(c.second));
    btDispatcher& dispatcher = *w.world().getDispatcher();
    for (int m = 0; m < dispatcher.getNumManifolds(); ++m) dispatcher.getManifoldByIndexInternal(m)->clearManifold();
    w.world().performDiscreteCollisionDetection();
    std::optional<double> distance;
    Eigen::Vector3d normal = Eigen::Vector3d::Zero();
    for (int m = 0; m < dispatcher.getNumManifolds(); ++m) {
      const btPersistentManifold& manifold = *dispatcher.getManifoldByIndexInternal(m);
      const double sign = manifold.getBody0() == &first ? 1.0 : -1.0;  // Bullet's normal: from body1 to body0
      for (int k = 0; k < manifold.getNumContacts(); ++k) {
        const btManifoldPoint& p = manifold.getContactPoint(k);
        if (distance && double(p.getDistance()) >= *distance) continue;
        distance = double(p.getDistance());
        normal = sign * toEigen(p.m_normalWorldOnB);
      }
    }
    ++s.cases;
    if (!distance || *distance >= 0.0) {
      ++s.missed;
      continue;
    }
    const double cosine = std::clamp(normal.normalized().dot(c.normal), -1.0, 1.0);
    const double error = std::fabs(-*distance - c.depth), angle = std::acos(cosine) * 180.0 / kPi;
    const bool epa = c.depth > margins;
    s.core_overlaps += epa;
    double& worst_error = epa ? s.worst_depth_error_epa : s.worst_depth_error;
    double& worst_angle = epa ? s.worst_angle_deg_epa : s.worst_angle_deg;
    worst_error = std::max(worst_error, error);
    worst_angle = std::max(worst_angle, angle);
  }
  return s;
}

constexpr int kCases = 300;

// A random point outside a core (given by its closest-point function), its nearest core point
// and the outward direction there.
template <class Closest>
void outside(Random& rng, const Eigen::Vector3d& reach, Closest closest, Eigen::Vector3d& q, Eigen::Vector3d& n) {
  for (;;) {
    const Eigen::Vector3d y(rng.uniform(-reach.x(), reach.x()), rng.uniform(-reach.y(), reach.y()),
                            rng.uniform(-reach.z(), reach.z()));
    q = closest(y);
    if ((y - q).norm() < 1e-4) continue;  // inside or too close to tell the direction
    n = (y - q).normalized();
    return;
  }
}

Eigen::Vector3d closestOnBox(const Eigen::Vector3d& core_half, const Eigen::Vector3d& y) {
  return y.cwiseMax(-core_half).cwiseMin(core_half);
}

Eigen::Vector3d closestOnCylinder(double core_r, double core_half_length, const Eigen::Vector3d& y) {
  Eigen::Vector2d xy = y.head<2>();
  if (xy.norm() > core_r) xy *= core_r / xy.norm();
  return {xy.x(), xy.y(), std::clamp(y.z(), -core_half_length, core_half_length)};
}

Eigen::Isometry3d pose(const Eigen::Quaterniond& q, const Eigen::Vector3d& p) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = q.toRotationMatrix();
  t.translation() = p;
  return t;
}

// A sphere of radius r around a core (closest-point function, in the core's frame), anywhere.
template <class Closest>
std::vector<PairCase> sphereAround(double r, double core_margin, const Eigen::Vector3d& reach, Closest closest) {
  Random rng;
  std::vector<PairCase> cases;
  for (int k = 0; k < kCases; ++k) {
    Eigen::Vector3d q, n;
    outside(rng, reach, closest, q, n);
    PairCase c;
    c.depth = rng.uniform(0.05e-3, 2e-3);
    const Eigen::Quaterniond turn = rng.rotation();
    c.second = pose(turn, rng.uniform(-0.05, 0.05) * Eigen::Vector3d::Ones());
    c.first = pose(rng.rotation(), c.second * (q + (r + core_margin - c.depth) * n));
    c.normal = turn * n;
    cases.push_back(c);
  }
  return cases;
}

// Two upright shapes (axes along z, centred at the same height) whose horizontal sections are a
// circle of core radius `core_r` (first) and a core the closest-point function describes
// (second, turned about z): the overlap is horizontal, margins + core radius - distance.
template <class Closest>
std::vector<PairCase> sideBySide(double core_r, double margins, double reach_xy, Closest closest) {
  Random rng;
  std::vector<PairCase> cases;
  for (int k = 0; k < kCases; ++k) {
    Eigen::Vector3d q, n;
    outside(rng, {reach_xy, reach_xy, 1e-9}, closest, q, n);
    PairCase c;
    c.depth = rng.uniform(0.05e-3, 2e-3);
    const Eigen::Quaterniond turn(Eigen::AngleAxisd(rng.uniform(-kPi, kPi), Eigen::Vector3d::UnitZ()));
    c.second = pose(turn, Eigen::Vector3d::Zero());
    c.first = pose(Eigen::Quaterniond::Identity(), turn * (q + (core_r + margins - c.depth) * n));
    c.normal = turn * n;
    cases.push_back(c);
  }
  return cases;
}

// A round shape (axis along its local z) against a box face: lying with its axis along the face
// (`lying`) or standing on it, end first. Depth along the face normal.
std::vector<PairCase> againstBoxFace(double half_box, double reach_along_face, double touch_extent, bool lying) {
  Random rng;
  std::vector<PairCase> cases;
  for (int k = 0; k < kCases; ++k) {
    PairCase c;
    c.depth = rng.uniform(0.05e-3, 2e-3);
    const Eigen::Quaterniond box_turn = rng.rotation();
    c.second = pose(box_turn, Eigen::Vector3d::Zero());
    const Eigen::Matrix3d faces = box_turn.toRotationMatrix();
    const int face = int(rng.uniform(0, 6));
    const Eigen::Vector3d n = (face % 2 ? 1.0 : -1.0) * faces.col(face / 2);
    const Eigen::Vector3d u = faces.col((face / 2 + 1) % 3), v = faces.col((face / 2 + 2) % 3);
    const Eigen::Vector3d on_face = half_box * n + rng.uniform(-reach_along_face, reach_along_face) * u +
                                    rng.uniform(-reach_along_face, reach_along_face) * v;
    // Axis: along the face at a random angle, or along n.
    const double angle = rng.uniform(-kPi, kPi);
    const Eigen::Vector3d axis = lying ? Eigen::Vector3d(std::cos(angle) * u + std::sin(angle) * v) : n;
    const Eigen::Quaterniond shape_turn =
        Eigen::Quaterniond(Eigen::AngleAxisd(angle, axis)) * Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), axis);
    c.first = pose(shape_turn, on_face + (touch_extent - c.depth) * n);
    c.normal = n;
    cases.push_back(c);
  }
  return cases;
}

void report(const char* pair, const Stats& scaled, const Stats& bullet) {
  std::printf("[measured] %-36s scaled: %d/%d missed; cores apart: depth error <= %.2f um, normal <= %.2f deg; "
              "cores overlapping (%d): <= %.2f um, <= %.2f deg | Bullet convex-convex: %d missed (%.0f %%), "
              "depth error <= %.0f um\n",
              pair, scaled.missed, scaled.cases, scaled.worst_depth_error * 1e6, scaled.worst_angle_deg,
              scaled.core_overlaps, scaled.worst_depth_error_epa * 1e6, scaled.worst_angle_deg_epa, bullet.missed,
              100.0 * bullet.missed / bullet.cases, std::max(bullet.worst_depth_error, bullet.worst_depth_error_epa) * 1e6);
}

// Stated tolerances, over 0.05-2 mm overlaps: none missed; depth within 40 µm and the normal
// within 6° in either regime (GJK and EPA on a cylinder's curved side stop on tolerances of
// their own; flat faces and spheres come out within 1 µm and 0.2°, printed above).
void expectExact(const char* pair, const Stats& s) {
  EXPECT_EQ(s.missed, 0) << pair;
  EXPECT_LT(s.worst_depth_error, 40e-6) << pair;
  EXPECT_LT(s.worst_angle_deg, 6.0) << pair;
  EXPECT_LT(s.worst_depth_error_epa, 40e-6) << pair;
  EXPECT_LT(s.worst_angle_deg_epa, 6.0) << pair;
}

void checkPair(const char* pair, const Shape& a, const Shape& b, const std::vector<PairCase>& cases) {
  const Stats scaled = measure(a, b, cases, Engine::Scaled);
  report(pair, scaled, measure(a, b, cases, Engine::BulletConvexConvex));
  expectExact(pair, scaled);
  // Either order of the pair: the same answers.
  std::vector<PairCase> swapped = cases;
  for (PairCase& c : swapped) std::swap(c.first, c.second), c.normal = -c.normal;
  expectExact(pair, measure(b, a, swapped, Engine::Scaled));
}

const Eigen::Vector3d kBoxHalf(0.006, 0.010, 0.004);  // a letter block's size range
constexpr double kBallR = 0.008, kCylR = 0.008, kCylHalf = 0.008;

TEST(ShapePairs, SphereBox) {
  const Eigen::Vector3d core = kBoxHalf - Eigen::Vector3d::Constant(kMargin);
  const auto cases = sphereAround(kBallR, kMargin, 2.0 * kBoxHalf, [&](const Eigen::Vector3d& y) { return closestOnBox(core, y); });
  checkPair("sphere-box (anywhere around it)", sphere(kBallR), box(kBoxHalf), cases);
  const Stats dedicated = measure(sphere(kBallR), box(kBoxHalf), cases, Engine::BulletSphereBox);
  std::printf("[measured] sphere-box, Bullet's btSphereBoxCollisionAlgorithm: %d/%d missed, depth error <= %.2f um, "
              "normal <= %.3f deg\n", dedicated.missed, dedicated.cases, dedicated.worst_depth_error * 1e6,
              dedicated.worst_angle_deg);
}

TEST(ShapePairs, SphereCylinder) {
  const auto cases = sphereAround(kBallR, kMargin, Eigen::Vector3d(0.02, 0.02, 0.02), [](const Eigen::Vector3d& y) {
    return closestOnCylinder(kCylR - kMargin, kCylHalf - kMargin, y);
  });
  checkPair("sphere-cylinder (anywhere around it)", sphere(kBallR), cylinder(kCylR, kCylHalf), cases);
}

TEST(ShapePairs, BoxCylinderSideBySide) {
  // An upright block's side against a standing post (letter_blocks.yaml's kind of contact):
  // a 2 x 2 x 1 cm block, the post 16 mm tall.
  const Eigen::Vector3d half(0.01, 0.01, 0.005), core = half - Eigen::Vector3d::Constant(kMargin);
  const auto cases = sideBySide(kCylR - kMargin, 2 * kMargin, 0.02, [&](const Eigen::Vector3d& y) {
    return Eigen::Vector3d(closestOnBox(core, {y.x(), y.y(), 0.0}));
  });
  checkPair("box-cylinder (upright, side by side)", cylinder(kCylR, kCylHalf), box(half), cases);
}

TEST(ShapePairs, CylinderOnBoxFace) {
  const Eigen::Vector3d half = Eigen::Vector3d::Constant(0.015);
  checkPair("cylinder lying on a box face", cylinder(kCylR, kCylHalf), box(half), againstBoxFace(0.015, 0.006, kCylR, true));
  checkPair("cylinder standing on a box face", cylinder(kCylR, kCylHalf), box(half),
            againstBoxFace(0.015, 0.006, kCylHalf, false));
}

TEST(ShapePairs, CapsuleBox) {
  const Eigen::Vector3d half = Eigen::Vector3d::Constant(0.015);
  checkPair("capsule lying on a box face", capsule(0.004, 0.006), box(half), againstBoxFace(0.015, 0.004, 0.004, true));
  checkPair("capsule standing on a box face", capsule(0.004, 0.006), box(half), againstBoxFace(0.015, 0.006, 0.010, false));
}

TEST(ShapePairs, CapsuleAndCylinderSideBySide) {
  const auto circle = [](double r) {
    return [r](const Eigen::Vector3d& y) { return Eigen::Vector3d(closestOnCylinder(r, 0.0, {y.x(), y.y(), 0.0})); };
  };
  checkPair("capsule-cylinder (standing)", capsule(0.004, 0.006), cylinder(kCylR, kCylHalf),
            sideBySide(0.004, kMargin, 0.02, circle(kCylR - kMargin)));
  checkPair("cylinder-cylinder (standing)", cylinder(0.005, 0.006), cylinder(kCylR, kCylHalf),
            sideBySide(0.005 - kMargin, 2 * kMargin, 0.02, circle(kCylR - kMargin)));
}

}  // namespace
}  // namespace thx::phys::test::test_shape_pairs
