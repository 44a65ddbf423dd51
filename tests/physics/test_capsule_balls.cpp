// Which balls of a capsule meet a triangle (clients/physics/capsule_balls.hpp): the segment's
// point nearest the triangle against a dense sampling, its run over the triangle against the
// projection's barycentric coordinates, and the search along a run for the least gap.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "clients/physics/capsule_balls.hpp"
#include "meshes/textured_mesh.hpp"

namespace thx::phys::test::test_capsule_balls {
namespace {

Eigen::Vector3d randomPoint(std::mt19937& rng, double spread) {
  std::uniform_real_distribution<double> u(-spread, spread);
  return {u(rng), u(rng), u(rng)};
}

// Whether p lies over the triangle: its projection on the plane has no negative barycentric.
bool over(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& p2, const Eigen::Vector3d& p) {
  const Eigen::Vector3d n = (p1 - p0).cross(p2 - p0).normalized();
  const Eigen::Vector3d projected = p - n.dot(p - p0) * n;
  const Eigen::Vector3d b = mesh::closestBarycentric(p0, p1, p2, projected);
  return ((b.x() * p0 + b.y() * p1 + b.z() * p2) - projected).norm() < 1e-12;
}

TEST(CapsuleBalls, TheNearestPointIsNoFartherThanAnySampleOfTheSegment) {
  std::mt19937 rng(29);
  int with_run = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const Eigen::Vector3d p0 = randomPoint(rng, 1.0), p1 = randomPoint(rng, 1.0), p2 = randomPoint(rng, 1.0);
    const Eigen::Vector3d a = randomPoint(rng, 1.5), b = trial % 4 == 0 ? a : randomPoint(rng, 1.5);
    const SegmentOverTriangle s = segmentOverTriangle(p0, p1, p2, a, b);
    const double nearest = distanceToTriangle(p0, p1, p2, a + s.nearest_t * (b - a));
    for (int k = 0; k <= 2000; ++k) {
      const double t = k / 2000.0;
      ASSERT_LE(nearest, distanceToTriangle(p0, p1, p2, a + t * (b - a)) + 1e-12) << "trial " << trial << " t " << t;
    }
    if (!s.runs_over) continue;
    ++with_run;
    ASSERT_LE(s.lo, s.hi);
    for (const double t : {s.lo, 0.5 * (s.lo + s.hi), s.hi}) EXPECT_TRUE(over(p0, p1, p2, a + t * (b - a))) << trial;
    if ((b - a).norm() > 1e-3) {
      if (s.lo > 1e-4) {
        EXPECT_FALSE(over(p0, p1, p2, a + (s.lo - 1e-4) * (b - a))) << trial;
      }
      if (s.hi < 1.0 - 1e-4) {
        EXPECT_FALSE(over(p0, p1, p2, a + (s.hi + 1e-4) * (b - a))) << trial;
      }
    }
  }
  std::printf("[measured] %d of 400 random segments ran over their triangle\n", with_run);
  EXPECT_GT(with_run, 40);
}

// A segment lying parallel over a face runs over it wholly; one standing beside its edge is
// nearest at the edge's height.
TEST(CapsuleBalls, ASegmentAlongAFaceRunsOverItAndOneBesideItIsNearestAtItsEdge) {
  const Eigen::Vector3d p0(0, 0, 0), p1(1, 0, 0), p2(0, 1, 0);
  const SegmentOverTriangle lying = segmentOverTriangle(p0, p1, p2, {0.1, 0.2, 0.05}, {0.6, 0.2, 0.05});
  EXPECT_TRUE(lying.runs_over);
  EXPECT_DOUBLE_EQ(lying.lo, 0.0);
  EXPECT_DOUBLE_EQ(lying.hi, 1.0);
  // Upright beside the edge along x (y < 0), from below the face to above it.
  const SegmentOverTriangle beside = segmentOverTriangle(p0, p1, p2, {0.3, -0.1, -0.2}, {0.3, -0.1, 0.6});
  EXPECT_FALSE(beside.runs_over);
  EXPECT_NEAR(beside.nearest_t, 0.25, 1e-12);  // z = 0
}

// The least of a gap along a run, on each half: two crests a ball rides (sphere caps, the gap's
// least at each cap's top) found to within a millionth of the run; a level gap gives the run's
// ends; a point, one ball.
TEST(CapsuleBalls, TheLeastGapOnEachHalfOfARunIsFoundBetweenSamples) {
  const auto cap = [](double t, double top) { return std::sqrt(std::max(0.0, 0.25 - (t - top) * (t - top))); };
  const auto crests = [&](double t) { return -std::max(cap(t, 0.2137), cap(t, 0.7771)); };
  const RunBalls two = leastOnHalves(0.0, 1.0, 0.05, 0.0, crests);
  ASSERT_EQ(two.count, 2);
  EXPECT_NEAR(two.t[0], 0.2137, 1e-6);
  EXPECT_NEAR(two.t[1], 0.7771, 1e-6);
  const RunBalls level = leastOnHalves(0.1, 0.9, 0.05, 1e-9, [](double) { return 1.0; });
  ASSERT_EQ(level.count, 2);
  EXPECT_DOUBLE_EQ(level.t[0], 0.1);
  EXPECT_DOUBLE_EQ(level.t[1], 0.9);
  const RunBalls point = leastOnHalves(0.3, 0.3, 0.05, 1e-9, [](double) { return 1.0; });
  ASSERT_EQ(point.count, 1);
  EXPECT_DOUBLE_EQ(point.t[0], 0.3);
  // One smooth least in the lower half: the upper half's least is at its own inner end, beside it.
  const RunBalls one = leastOnHalves(0.0, 1.0, 0.01, 0.0, [](double t) { return (t - 0.3) * (t - 0.3); });
  EXPECT_NEAR(one.t[0], 0.3, 1e-5);
}

}  // namespace
}  // namespace thx::phys::test::test_capsule_balls
