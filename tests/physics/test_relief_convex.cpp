// A round object cresting a CONVEX relief (a bump). The tangent plane of a texel away from the
// point of contact lies above a convex relief and would cut into the ball, pushing it up: before
// the fix in relief_collision.cpp a 1 cm ball cresting a 1 mm bump was lifted 55 µm above the
// bump and gained 1.4 % energy, and escaped 4 % below the energy threshold (bench_physics).
#include <gtest/gtest.h>

#include <cstdio>

#include "physics_fixtures.hpp"

namespace thx::phys::test::test_relief_convex {
namespace {

constexpr double kRadius = 0.01, kMass = 0.05, kExtent = 0.1, kH = 1e-3, kW = 0.03;
constexpr int kSize = 256;  // 0.39 mm texels

double bump(double x, double) { return std::fabs(x) < 0.5 * kW ? kH * std::pow(std::cos(kPi * x / kW), 2) : 0.0; }

struct Crest {
  bool escaped = false;
  double e_max_ratio = 0.0;  // max total energy / initial
  double lift = 0.0;         // max (z - r) of the centre above the flat ground
};

// The relief plane sits at the bump's top; the flat ground is at z = -H in its frame.
Crest launch(const SurfaceHolder& s, double v) {
  PhysicsWorld w;
  w.addReliefPlane(s.surface, {1.0, 0.0, 0.0});
  const double ground = -kH, x0 = -0.5 * kW - 0.012;
  btRigidBody& ball = w.addSphere(kRadius, kMass, at(x0, 0, ground + kRadius), {0.8, 0.0, 0.0});
  setRolling(ball, v, kRadius);
  const double inertia = 0.4 * kMass * kRadius * kRadius;
  auto energy = [&] {
    return 0.5 * kMass * velocityOf(ball).squaredNorm() + 0.5 * inertia * angularVelocityOf(ball).squaredNorm() +
           kMass * kG * positionOf(ball).z();
  };
  const double e0 = energy();
  Crest c;
  for (int k = 0; k < 1200; ++k) {
    w.step(1e-3);
    c.e_max_ratio = std::max(c.e_max_ratio, energy() / e0);
    c.lift = std::max(c.lift, positionOf(ball).z() - ground - kRadius);
    if (positionOf(ball).x() > 0.5 * kW + 0.004) return c.escaped = true, c;
    if (velocityOf(ball).x() < 0.0 && positionOf(ball).x() < x0) return c;
  }
  return c;
}

TEST(ConvexRelief, ABallCrestingABumpGainsNoEnergyAndIsNotLifted) {
  const SurfaceHolder s = holdSurface(heightMap(kSize, kExtent, bump), kExtent, true);
  const double v_c = std::sqrt(10.0 / 7.0 * kG * kH);
  const Crest c = launch(s, 1.1 * v_c);
  std::printf("[measured] 1 cm ball over a 1 mm bump at 1.1 v_c: E_max/E0 = %.5f, centre up to %.1f µm above r\n",
              c.e_max_ratio, 1e6 * c.lift);
  EXPECT_TRUE(c.escaped);
  EXPECT_LT(c.e_max_ratio, 1.002) << "no energy from the contacts";
  EXPECT_LT(c.lift, kH + 5e-6) << "the centre rises by the bump's height, not more";
}

TEST(ConvexRelief, EscapeSpeedOfA1cmBallMatchesTheEnergyThreshold) {
  const SurfaceHolder s = holdSurface(heightMap(kSize, kExtent, bump), kExtent, true);
  const double v_c = std::sqrt(10.0 / 7.0 * kG * kH);
  double lo = 0.9 * v_c, hi = 1.1 * v_c;
  ASSERT_FALSE(launch(s, lo).escaped);
  ASSERT_TRUE(launch(s, hi).escaped);
  for (int i = 0; i < 5; ++i) {  // bracket 0.2 v_c / 32: ±0.3 %
    const double mid = 0.5 * (lo + hi);
    (launch(s, mid).escaped ? hi : lo) = mid;
  }
  const double measured = 0.5 * (lo + hi);
  std::printf("[measured] 1 cm ball: v_c = %.5f m/s, energy threshold %.5f (%+.2f %%)\n", measured, v_c,
              100.0 * (measured / v_c - 1.0));
  EXPECT_NEAR(measured, v_c, 0.015 * v_c);
}

}  // namespace
}  // namespace thx::phys::test::test_relief_convex
