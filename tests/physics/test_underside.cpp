// underside.*: the lowest point of a sphere / box / capsule / cylinder on a vertical line, its
// plane-frame bounds and the contact point on round parts, against closed forms and against a
// brute-force search with an inside-the-solid test.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>
#include <random>

#include "clients/physics/underside.hpp"

namespace thx::phys::test_underside {
namespace {

constexpr double kPi = std::numbers::pi;

Eigen::Isometry3d pose(const Eigen::Vector3d& c, const Eigen::Matrix3d& r = Eigen::Matrix3d::Identity()) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = r;
  t.translation() = c;
  return t;
}

Eigen::Matrix3d randomRotation(std::mt19937& rng) {
  std::normal_distribution<double> g;
  return Eigen::Quaterniond(g(rng), g(rng), g(rng), g(rng)).normalized().toRotationMatrix();
}

// Is p inside (or on) the solid? Plane-frame point. Written in plain doubles, not Eigen
// expressions: the brute force below calls it about 1.5 million times, and the sanitizer tree
// builds test files at -O0, where Eigen's expression templates made this test take 7 s instead of
// 0.04 s (docs/build.md).
bool inside(const Underside& s, const Eigen::Vector3d& p) {
  const double* m = s.plane_from_object.matrix().data();  // 4x4, column-major
  const double d[3] = {p[0] - m[12], p[1] - m[13], p[2] - m[14]};
  double q[3];  // object frame: q = R^T d, R's column i at m[4i..4i+2]
  for (int i = 0; i < 3; ++i) q[i] = m[4 * i] * d[0] + m[4 * i + 1] * d[1] + m[4 * i + 2] * d[2];
  const auto norm = [](double a, double b, double c) { return std::sqrt(a * a + b * b + c * c); };
  switch (s.kind) {
    case Underside::Kind::Sphere:
      return norm(q[0], q[1], q[2]) <= s.radius;
    case Underside::Kind::Box:
      return std::fabs(q[0]) <= s.half_extents[0] && std::fabs(q[1]) <= s.half_extents[1] &&
             std::fabs(q[2]) <= s.half_extents[2];
    case Underside::Kind::Capsule: {
      double r[3] = {q[0], q[1], q[2]};  // from the nearest point of the axis segment
      r[s.axis] -= std::clamp(q[s.axis], -s.half_length, s.half_length);
      return norm(r[0], r[1], r[2]) <= s.radius;
    }
    case Underside::Kind::Cylinder: {
      double r[3] = {q[0], q[1], q[2]};
      r[s.axis] = 0.0;
      return std::fabs(q[s.axis]) <= s.half_length && norm(r[0], r[1], r[2]) <= s.radius;
    }
  }
  return false;
}

// Brute force: scan the vertical line upwards in fine steps for the first inside point, then
// bisect between the last outside and the first inside sample.
std::optional<double> scanLowestZ(const Underside& s, double x, double y) {
  const Eigen::AlignedBox3d b = planeBounds(s);
  const double z0 = b.min().z() - 1e-4, z1 = b.max().z() + 1e-4;
  const int steps = 2000;
  const double dz = (z1 - z0) / steps;
  for (int k = 1; k <= steps; ++k) {
    const double z = z0 + k * dz;
    if (!inside(s, {x, y, z})) continue;
    double lo = z - dz, hi = z;
    for (int it = 0; it < 50; ++it) {
      const double mid = 0.5 * (lo + hi);
      (inside(s, {x, y, mid}) ? hi : lo) = mid;
    }
    return hi;
  }
  return std::nullopt;
}

TEST(Underside, SphereClosedForm) {
  const Underside s = Underside::sphere(pose({0.01, -0.02, 0.03}), 0.005);
  EXPECT_NEAR(*lowestZ(s, 0.01, -0.02), 0.025, 1e-15);
  EXPECT_NEAR(*lowestZ(s, 0.013, -0.02), 0.03 - std::sqrt(0.005 * 0.005 - 0.003 * 0.003), 1e-15);
  EXPECT_FALSE(lowestZ(s, 0.0151, -0.02).has_value()) << "outside the disc";
  const Eigen::AlignedBox3d b = planeBounds(s);
  EXPECT_TRUE(b.min().isApprox(Eigen::Vector3d(0.005, -0.025, 0.025)));
  EXPECT_TRUE(b.max().isApprox(Eigen::Vector3d(0.015, -0.015, 0.035)));
}

TEST(Underside, AxisAlignedBoxIsFlatUnderneath) {
  const Underside s = Underside::box(pose({0, 0, 0.01}), {0.02, 0.01, 0.005});
  for (double x : {-0.0199, 0.0, 0.015})
    for (double y : {-0.0099, 0.003}) EXPECT_NEAR(*lowestZ(s, x, y), 0.005, 1e-15) << x << " " << y;
  EXPECT_FALSE(lowestZ(s, 0.0201, 0.0).has_value());
  EXPECT_FALSE(lowestZ(s, 0.0, -0.0101).has_value());
}

TEST(Underside, TiltedBoxFollowsItsBottomFace) {
  // Tilted by a about y: the bottom face is the plane through c - h_z n_z with normal R e_z.
  const double a = 0.3, h = 0.01;
  const Eigen::Matrix3d r = Eigen::AngleAxisd(a, Eigen::Vector3d::UnitY()).toRotationMatrix();
  const Underside s = Underside::box(pose({0, 0, 0.05}, r), {h, h, h});
  // Near the middle the bottom face is what the line enters: z = c_z - h / cos a + x tan a... with
  // the face normal n = R e_z = (sin a, 0, cos a): n·(p - (c - h n)) = 0.
  for (double x : {-0.004, 0.0, 0.004}) {
    const double expected = 0.05 - h / std::cos(a) - x * std::tan(a);
    EXPECT_NEAR(*lowestZ(s, x, 0.0), expected, 1e-14) << x;
  }
}

TEST(Underside, CapsuleLyingAndStanding) {
  const double r = 0.004, hl = 0.01;
  const Eigen::Matrix3d lying = Eigen::AngleAxisd(kPi / 2, Eigen::Vector3d::UnitX()).toRotationMatrix();  // axis along -y
  const Underside s = Underside::capsule(pose({0, 0, r}, lying), r, hl);
  EXPECT_NEAR(*lowestZ(s, 0.0, 0.0), 0.0, 1e-15) << "the side touches the plane";
  EXPECT_NEAR(*lowestZ(s, 0.002, 0.005), r - std::sqrt(r * r - 0.002 * 0.002), 1e-15) << "side, off the axis";
  EXPECT_NEAR(*lowestZ(s, 0.0, hl + 0.003), r - std::sqrt(r * r - 0.003 * 0.003), 1e-15) << "end cap";
  EXPECT_FALSE(lowestZ(s, 0.0, hl + r + 1e-4).has_value());
  const Underside standing = Underside::capsule(pose({0, 0, hl + r}), r, hl);
  EXPECT_NEAR(*lowestZ(standing, 0.0, 0.0), 0.0, 1e-15) << "the bottom cap's pole";
}

TEST(Underside, CylinderStandingAndLying) {
  const double r = 0.004, hl = 0.01;
  const Underside standing = Underside::cylinder(pose({0, 0, hl}), r, hl);
  EXPECT_NEAR(*lowestZ(standing, 0.003, -0.002), 0.0, 1e-15) << "flat end face";
  EXPECT_FALSE(lowestZ(standing, 0.0041, 0.0).has_value());
  const Eigen::Matrix3d lying = Eigen::AngleAxisd(kPi / 2, Eigen::Vector3d::UnitX()).toRotationMatrix();
  const Underside side = Underside::cylinder(pose({0, 0, r}, lying), r, hl);
  EXPECT_NEAR(*lowestZ(side, 0.001, 0.009), r - std::sqrt(r * r - 0.001 * 0.001), 1e-15);
  EXPECT_FALSE(lowestZ(side, 0.0, hl + 1e-4).has_value()) << "flat ends: nothing beyond them";
}

// Every shape in random poses: lowestZ agrees with the brute-force search, and its point is on
// the solid's boundary (inside just above, outside just below).
TEST(Underside, RandomPosesAgreeWithBruteForce) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int hits = 0, misses = 0;
  for (int trial = 0; trial < 30; ++trial) {
    const Eigen::Isometry3d p = pose({0.0, 0.0, 0.02}, randomRotation(rng));
    const Underside shapes[] = {Underside::sphere(p, 0.006), Underside::box(p, {0.008, 0.005, 0.003}),
                                Underside::capsule(p, 0.003, 0.006, trial % 3),
                                Underside::cylinder(p, 0.004, 0.005, trial % 3)};
    for (const Underside& s : shapes) {
      for (int k = 0; k < 6; ++k) {
        const double x = 0.009 * u(rng), y = 0.009 * u(rng);
        const std::optional<double> z = lowestZ(s, x, y);
        const std::optional<double> ref = scanLowestZ(s, x, y);
        if (!ref) {
          // The scan steps about 15 µm: where it finds nothing, lowestZ may only find a sliver.
          if (z) {
            EXPECT_TRUE(inside(s, {x, y, *z + 1e-9})) << "kind " << int(s.kind);
          }
          ++misses;
          continue;
        }
        ++hits;
        ASSERT_TRUE(z.has_value()) << "kind " << int(s.kind) << " at " << x << ", " << y;
        EXPECT_NEAR(*z, *ref, 1e-9) << "kind " << int(s.kind) << " trial " << trial;
        EXPECT_FALSE(inside(s, {x, y, *z - 1e-7})) << "kind " << int(s.kind);
        EXPECT_TRUE(inside(s, {x, y, *z + 1e-9}) || inside(s, {x, y, *z + 1e-7})) << "kind " << int(s.kind);
      }
    }
  }
  EXPECT_GT(hits, 150);
  EXPECT_GT(misses, 20) << "the samples also cover lines that miss";
}

// The bounds contain the solid (random points inside it stay within them), and their lowest z
// is where the underside really reaches (the minimum of lowestZ over a fine grid).
TEST(Underside, BoundsContainTheSolidAndReachItsBottom) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int trial = 0; trial < 10; ++trial) {
    const Eigen::Isometry3d p = pose({0.001, -0.002, 0.01}, randomRotation(rng));
    for (const Underside& s : {Underside::sphere(p, 0.005), Underside::box(p, {0.006, 0.004, 0.002}),
                               Underside::capsule(p, 0.002, 0.005, 1), Underside::cylinder(p, 0.003, 0.004, 0)}) {
      const Eigen::AlignedBox3d b = planeBounds(s);
      const Eigen::Vector3d margin = Eigen::Vector3d::Constant(1e-3);
      int inside_count = 0;
      for (int k = 0; k < 4000; ++k) {
        // One draw a statement, in g++'s order of a call's arguments (unspecified by C++), so
        // every compiler draws these points.
        const double tz = u(rng), ty = u(rng), tx = u(rng);
        const Eigen::Vector3d t(tx, ty, tz);
        const Eigen::Vector3d q = (b.min() - margin) + (b.max() - b.min() + 2.0 * margin).cwiseProduct(t);
        if (!inside(s, q)) continue;
        ++inside_count;
        EXPECT_TRUE(b.contains(q)) << "kind " << int(s.kind) << " trial " << trial;
      }
      EXPECT_GT(inside_count, 100);
      double z_min = 1e9;
      const int n = 100;
      for (int i = 0; i <= n; ++i)
        for (int j = 0; j <= n; ++j) {
          const double x = b.min().x() + (b.max().x() - b.min().x()) * i / n;
          const double y = b.min().y() + (b.max().y() - b.min().y()) * j / n;
          if (const std::optional<double> z = lowestZ(s, x, y)) z_min = std::min(z_min, *z);
        }
      EXPECT_GE(z_min, b.min().z() - 1e-12) << "kind " << int(s.kind);
      EXPECT_LT(z_min - b.min().z(), 0.05 * (b.max().z() - b.min().z())) << "kind " << int(s.kind) << " trial " << trial;
    }
  }
}

TEST(Underside, ContactPointOnRoundPartsFacesMinusN) {
  const Eigen::Vector3d n = Eigen::Vector3d(0.2, -0.1, 1.0).normalized();
  const Underside ball = Underside::sphere(pose({0.01, 0.02, 0.005}), 0.005);
  EXPECT_TRUE(contactOnObject(ball, {0.01, 0.02, 0.0}, n).isApprox(Eigen::Vector3d(0.01, 0.02, 0.005) - 0.005 * n))
      << "Eq. 2: q = c - r n";

  const Underside box = Underside::box(pose({0, 0, 0.01}), {0.01, 0.01, 0.01});
  const Eigen::Vector3d corner(0.01, -0.01, 0.0);
  EXPECT_TRUE(contactOnObject(box, corner, n).isApprox(corner)) << "flat parts keep their point";

  // Capsule lying along y: on its side the point is the axis point minus r times n's part
  // across the axis (n's y component is dropped), so the push passes through the axis.
  const double r = 0.004;
  const Eigen::Matrix3d lying = Eigen::AngleAxisd(kPi / 2, Eigen::Vector3d::UnitX()).toRotationMatrix();
  const Underside cap = Underside::capsule(pose({0, 0, r}, lying), r, 0.01);
  const Eigen::Vector3d q = contactOnObject(cap, {0.0, 0.003, 0.0}, n);
  const Eigen::Vector3d across = Eigen::Vector3d(n.x(), 0.0, n.z()).normalized();
  EXPECT_TRUE(q.isApprox(Eigen::Vector3d(0.0, 0.003, r) - r * across, 1e-12)) << q.transpose();
  EXPECT_NEAR(std::hypot(q.x(), q.z() - r), r, 1e-15) << "on the capsule's surface";

  // A standing cylinder's end face is flat: its point is kept.
  const Underside cyl = Underside::cylinder(pose({0, 0, 0.01}), 0.004, 0.01);
  const Eigen::Vector3d on_face(0.002, 0.001, 0.0);
  EXPECT_TRUE(contactOnObject(cyl, on_face, n).isApprox(on_face));
}

}  // namespace
}  // namespace thx::phys::test_underside
