// Relief-map impulses from the contact's normal tick by tick (clients/audio/synthesis/relief_impulses.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "clients/audio/synthesis/relief_impulses.hpp"

namespace thx::audio::test_relief_impulses {
namespace {

ReliefTick tick(const Eigen::Vector3d& normal, const Eigen::Vector3d& velocity) {
  return {true, {0, 0, 1}, normal.normalized(), velocity};
}

TEST(ReliefImpulses, FlatReliefAndUniformSlopeGiveExactlyZero) {
  const Eigen::Vector3d v(0.1, 0.03, 0.0);
  EXPECT_EQ(reliefImpulse(tick({0, 0, 1}, v), tick({0, 0, 1}, v), 0.045), 0.0);
  const Eigen::Vector3d slope(0.3, -0.2, 1.0);
  EXPECT_EQ(reliefImpulse(tick(slope, v), tick(slope, v * 2), 0.045), 0.0);  // the hand speeds up: still none
}

TEST(ReliefImpulses, HandComputedStepOntoATiltedFacet) {
  // From flat onto a facet tilted 20 degrees about y (normal (sin 20, 0, cos 20)), sliding at
  // 0.1 m/s along +x with m = 0.045 kg: the pen must rise at v tan 20 = 0.036397 m/s, so
  // J = m (-(v . n)/(n_g . n) - 0) = -0.045 x 0.1 x tan 20 = -1.6379e-3 N s along n_g (this
  // facet falls away along +x, so the pen is pulled down onto it).
  const double a = 20.0 * std::numbers::pi / 180.0;
  const Eigen::Vector3d v(0.1, 0.0, 0.0), tilted(std::sin(a), 0.0, std::cos(a));
  const double in = reliefImpulse(tick({0, 0, 1}, v), tick(tilted, v), 0.045);
  EXPECT_NEAR(in, -0.045 * 0.1 * std::tan(a), 1e-15);
  EXPECT_NEAR(in, -1.6379e-3, 1e-7);
  // Back onto the flat: the opposite impulse.
  EXPECT_NEAR(reliefImpulse(tick(tilted, v), tick({0, 0, 1}, v), 0.045), -in, 1e-15);
  // The velocity's normal component is ignored; the mass scales it.
  EXPECT_NEAR(reliefImpulse(tick({0, 0, 1}, v), tick(tilted, v + Eigen::Vector3d(0, 0, 5)), 0.09), 2 * in, 1e-15);
}

TEST(ReliefImpulses, NoContactNoImpulseAndGrazingNormalsStayBounded) {
  const Eigen::Vector3d v(0.2, 0.0, 0.0);
  ReliefTick lifted = tick({0.5, 0, 1}, v);
  lifted.in_contact = false;
  EXPECT_EQ(reliefImpulse(lifted, tick({0, 0, 1}, v), 0.045), 0.0);
  EXPECT_EQ(reliefImpulse(tick({0, 0, 1}, v), lifted, 0.045), 0.0);
  // Nearly perpendicular normals: |J| <= m |v| (1/0.05 + 1/0.05) at the floor.
  const double j = reliefImpulse(tick({-1, 0, 1e-6}, v), tick({1, 0, 1e-6}, v), 0.045);
  EXPECT_TRUE(std::isfinite(j));
  EXPECT_LE(std::fabs(j), 2 * 0.045 * 0.2 / 0.05 + 1e-12);
}

}  // namespace
}  // namespace thx::audio::test_relief_impulses
