// A ball rolling across sine ridges of a relief laid on a mesh (the flat top of a box), against
// the rolling-impact reference (rolling_over_ridges.hpp): the product's lifted ball loses its speed
// where it cannot reach the troughs, as a rigid ball rolling without slipping does, and little
// where it can; the steered ball (MeshContactOptions::lift_ball false, held on the smooth surface)
// keeps it everywhere. The relief plane follows the law too since a ball's open points ahead are
// left out (speculative_contacts.hpp). benchmarks/bench_rolling_ridges.cpp measures them all.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "tests/physics/ridges_scene.hpp"
#include "tests/support/sanitized_build.hpp"

namespace thx::phys::test::test_relief_mesh_ridges {
namespace {

using namespace ridges;

TEST(ReliefMeshRidges, TheReferenceLosesSpeedAtTroughsSharperThanTheBall) {
  // The sine's trough curvature a (2 pi / P)^2 = s 2 pi / P against the ball's 1 / r = 100 per
  // metre: 50 and 251 per metre at slopes 0.02 and 0.1.
  const double a_gentle = amplitudeFor(0.02), a_steep = amplitudeFor(0.1);
  const RollingOverRidges gentle([&](double x) { return a_gentle * std::sin(2.0 * kPi * x / kPeriod); }, kPeriod,
                                 kRadius);
  const RollingOverRidges steep([&](double x) { return a_steep * std::sin(2.0 * kPi * x / kPeriod); }, kPeriod,
                                kRadius);
  EXPECT_EQ(gentle.jumps(), 0);
  EXPECT_EQ(steep.jumps(), 1);
  EXPECT_GT(steep.largestJumpAngle(), 0.1);
  const std::vector<double> kept = gentle.periodMeanSpeeds(0.2, 50), lost = steep.periodMeanSpeeds(0.2, 50);
  ASSERT_EQ(kept.size(), 50u);
  EXPECT_NEAR(kept.back(), kept.front(), 1e-9);
  ASSERT_EQ(lost.size(), 50u);
  // Nearly the kinetic energy alone at these speeds: v^2 falls by the factor squared a period.
  const double kept_squared = std::pow(steep.speedKeptPerPeriod(), 2.0 * 49.0);
  EXPECT_NEAR(lost[49] * lost[49] / (lost[0] * lost[0]), kept_squared, 0.05 * kept_squared);
  // As stored, the gentle ridges' inside corners between texels take a little at each.
  const RollingOverRidges stored = referenceFor(0.02);
  EXPECT_GT(stored.jumps(), 0);
  EXPECT_GT(stored.speedKeptPerPeriod(), 0.9999);
}

// The lifted ball on the mesh, and the ball on the relief plane.
TEST(ReliefMeshRidges, ALiftedBallSlowsAtTheTroughsAsARigidBallRollingWithoutSlippingDoes) {
  for (const double slope : {0.05, 0.1}) {
    const tex::TextureMap map = sineRidges(slope);
    const RollingOverRidges reference = referenceFor(slope);
    const double expected = speedKept(reference.periodMeanSpeeds(0.25, kFirst + kPeriods + 1));
    ASSERT_LT(expected, 0.9);
    for (const Ground ground : {Ground::MeshLifted, Ground::ReliefPlane}) {
      const bool plane = ground == Ground::ReliefPlane;
      // The plane rasterises the ball's footprint over 39 um texels: 0.45 ms a step here (0.6
      // before its normals were read at the contacts kept only), 30 ms under the sanitizers
      // then (107 s for its 1 ms steps alone). They need the code path, which every
      // relief-plane ball test runs; the statistics are the optimised tree's.
      if (plane && thx::test::kSanitized) continue;
      for (const double dt : {1e-3, 2.5e-4}) {
        const RidgeRun run = rollAcross(map, ground, dt, 0.25, 1.5);
        const double kept = speedKept(run.period_speeds);
        std::printf("[measured] %s, slope %.2f, step %.2g ms: %.4f of the speed kept over %d periods (the rolling-impact "
                    "law: %.4f, the touches' normals up to %.2f degrees apart at a trough); lowest %.1f um (%.1f)\n",
                    plane ? "relief plane" : "mesh, lifted", slope, dt * 1e3, kept, kPeriods, expected,
                    reference.largestJumpAngle() * 180.0 / kPi, run.lowest_m * 1e6, reference.lowest() * 1e6);
        // Measured on the mesh: -0.049 and -0.036 at slope 0.05 (1 and 0.25 ms), +0.046 and +0.003
        // at 0.1; a 1 ms step takes about 0.02 of its own (the next test). On the plane: -0.057 and
        // -0.009, -0.014 and -0.006; with its open points ahead taken, -0.161 / -0.045 and
        // -0.203 / -0.054.
        const double tolerance = plane ? (dt > 5e-4 ? 0.08 : 0.02) : 0.065;
        EXPECT_NEAR(kept, expected, tolerance) << (plane ? "plane" : "mesh") << ", slope " << slope << ", step " << dt;
        // It sinks between the crests as the rigid ball does (steered, it would stay on their tops).
        // On the plane an open point left out is met a step later, a little into the far flank:
        // measured 11 and 18 um below the rigid ball's lowest at 1 ms (slopes 0.05 and 0.1), 3 and
        // 5 um at 0.25 ms (with the open points taken: 4 and 0, 0.2 and 0).
        if (plane) {
          EXPECT_GT(run.lowest_m, reference.lowest() - (dt > 5e-4 ? 25e-6 : 8e-6)) << "slope " << slope << ", step " << dt;
        } else {
          EXPECT_LT(run.lowest_m, 0.5 * reference.lowest()) << "slope " << slope << ", step " << dt;
        }
      }
    }
  }
}

TEST(ReliefMeshRidges, ASteeredBallKeepsItsSpeedAndALiftedOneLosesLittleWhereItReachesTheTroughs) {
  const tex::TextureMap steep = sineRidges(0.1), gentle = sineRidges(0.02);
  // Where the ball reaches every trough only the stored ridges' corners between texels take speed.
  const double expected = referenceFor(0.02).speedKeptPerPeriod();
  EXPECT_GT(expected, 0.9999);
  for (const double dt : {1e-3, 2.5e-4}) {
    const double steered = speedKept(rollAcross(steep, Ground::MeshSteered, dt, 0.25, 1.2).period_speeds);
    const double reaching = speedKept(rollAcross(gentle, Ground::MeshLifted, dt, 0.25, 1.2).period_speeds);
    std::printf("[measured] step %.2g ms, speed kept over %d periods: steered on slope 0.1 %.4f, lifted on slope 0.02 "
                "%.4f (the rolling-impact law %.4f)\n",
                dt * 1e3, kPeriods, steered, reaching, std::pow(expected, kPeriods));
    // Measured 0.9866 and 0.9941 steered; lifted 0.966 and 0.982, what holding the gap to a
    // surface that rises and falls under the ball takes (the relief plane: 0.983 and 0.998).
    EXPECT_NEAR(steered, 1.0, dt > 5e-4 ? 0.02 : 0.01);
    EXPECT_GT(reaching, dt > 5e-4 ? 0.95 : 0.97);
  }
}

}  // namespace
}  // namespace thx::phys::test::test_relief_mesh_ridges
