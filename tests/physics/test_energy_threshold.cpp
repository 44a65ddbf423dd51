// Escape over a bump and trapping in a dimple against the energy threshold, for the normal-map
// and the relief representation of the same height field.
//
// A ball rolling without slip carries kinetic energy 7/10 m v^2. It clears a barrier of height H
// (the rise of its centre) iff 7/10 v^2 > g H, so v_c = sqrt(10/7 g H):
//  - relief: the centre rises by the bump's height H (the bump is gentler than the ball, so the
//    ball touches one point at a time), and climbs the depth d out of a dimple whose cap radius
//    exceeds the ball's;
//  - normal map: the flat plane holds the centre's height and the sampled normal at the point
//    below the centre pushes the ball as if it were at height h(x): the same barrier H or d.
// The threshold is measured by bisection on the launch speed and must agree within 5 %.
#include <gtest/gtest.h>

#include <cstdio>

#include "physics_fixtures.hpp"

namespace thx::phys::test::test_energy_threshold {
namespace {

constexpr double kDt = 1e-3, kRadius = 0.005, kMass = 0.01, kExtent = 0.1;
constexpr int kSize = 256;  // 0.39 mm texels

enum class Mode { Normal, Relief };
const char* name(Mode m) { return m == Mode::Normal ? "normal" : "relief"; }

// A ridge along y: h = H cos^2(pi x / w) for |x| < w/2. Its curvature radius w^2 / (2 pi^2 H)
// (4.6 cm here) exceeds the ball's radius everywhere, so the relief ball touches one point.
constexpr double kBumpH = 1e-3, kBumpW = 0.03;
double bump(double x, double) {
  return std::fabs(x) < 0.5 * kBumpW ? kBumpH * std::pow(std::cos(kPi * x / kBumpW), 2) : 0.0;
}

// One spherical-cap dimple at the origin: rim radius a, depth d, cap radius (a^2+d^2)/(2d).
constexpr double kDimpleA = 0.008, kDimpleD = 0.5e-3;
double dimple(double x, double y) {
  const double big_r = (kDimpleA * kDimpleA + kDimpleD * kDimpleD) / (2.0 * kDimpleD);
  const double r2 = x * x + y * y;
  return r2 < kDimpleA * kDimpleA ? -(std::sqrt(big_r * big_r - r2) - (big_r - kDimpleD)) : 0.0;
}

struct Launch {
  double x0;            // start (centre) x
  double z0;            // start (centre) z in the plane frame for the relief surface; r for normal
  double escape_x;      // beyond this the ball has escaped
  double give_up_s;     // simulated time limit
};

// True if a ball launched along +x at speed v (rolling) gets past escape_x.
bool escapes(const SurfaceHolder& s, Mode mode, const Launch& l, double v) {
  PhysicsWorld w;
  const BodyMaterial plane{1.0, 0.0, 0.0}, ball_m{0.8, 0.0, 0.0};
  if (mode == Mode::Normal) w.addNormalMapPlane(s.surface, plane); else w.addReliefPlane(s.surface, plane);
  btRigidBody& ball = w.addSphere(kRadius, kMass, at(l.x0, 0, mode == Mode::Normal ? kRadius : l.z0), ball_m);
  setRolling(ball, v, kRadius);
  const int steps = int(l.give_up_s / kDt);
  for (int k = 0; k < steps; ++k) {
    w.step(kDt);
    const Eigen::Vector3d p = positionOf(ball);
    if (p.x() > l.escape_x) return true;
    if (velocityOf(ball).x() < 0.0 && p.x() < l.x0) return false;  // came back
  }
  return false;
}

double bisectThreshold(const SurfaceHolder& s, Mode mode, const Launch& l, double v_guess) {
  double lo = 0.6 * v_guess, hi = 1.4 * v_guess;
  EXPECT_FALSE(escapes(s, mode, l, lo)) << name(mode) << ": escapes even at " << lo;
  EXPECT_TRUE(escapes(s, mode, l, hi)) << name(mode) << ": trapped even at " << hi;
  for (int i = 0; i < 7; ++i) {  // bracket width 0.8 v / 2^7 < 0.7 %
    const double mid = 0.5 * (lo + hi);
    (escapes(s, mode, l, mid) ? hi : lo) = mid;
  }
  return 0.5 * (lo + hi);
}

class EnergyThreshold : public ::testing::TestWithParam<Mode> {};

TEST_P(EnergyThreshold, EscapeOverABump) {
  const Mode mode = GetParam();
  const SurfaceHolder s = holdSurface(heightMap(kSize, kExtent, bump), kExtent, mode == Mode::Relief);
  // Relief: the plane sits at the bump's top (depth 0 there), the flat ground at z = -H.
  const Launch l{-0.5 * kBumpW - 0.005, -kBumpH + kRadius, 0.5 * kBumpW + 0.002, 1.5};
  const double expected = std::sqrt(10.0 / 7.0 * kG * kBumpH);
  const double measured = bisectThreshold(s, mode, l, expected);
  std::printf("[measured] %s v_c = %.5f m/s, energy threshold %.5f m/s (%+.2f %%)\n", name(mode), measured, expected,
              100.0 * (measured / expected - 1.0));
  EXPECT_NEAR(measured, expected, 0.05 * expected) << name(mode) << ": v_c measured " << measured;
}

TEST_P(EnergyThreshold, TrappedInADimple) {
  const Mode mode = GetParam();
  const SurfaceHolder s = holdSurface(heightMap(kSize, kExtent, dimple), kExtent, mode == Mode::Relief);
  // Relief: the dimple's bottom is the deepest point, the ball starts resting there.
  const Launch l{0.0, -kDimpleD + kRadius, kDimpleA + kRadius, 1.5};
  const double expected = std::sqrt(10.0 / 7.0 * kG * kDimpleD);
  const double measured = bisectThreshold(s, mode, l, expected);
  std::printf("[measured] %s v_c = %.5f m/s, energy threshold %.5f m/s (%+.2f %%)\n", name(mode), measured, expected,
              100.0 * (measured / expected - 1.0));
  EXPECT_NEAR(measured, expected, 0.05 * expected) << name(mode) << ": v_c measured " << measured;
}

INSTANTIATE_TEST_SUITE_P(Representation, EnergyThreshold, ::testing::Values(Mode::Normal, Mode::Relief),
                         [](const auto& p) { return std::string(name(p.param)); });

}  // namespace
}  // namespace thx::phys::test::test_energy_threshold
