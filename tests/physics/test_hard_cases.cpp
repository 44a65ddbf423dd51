// Numerical hard cases: near-grazing sampled normals, texture edges (clamp border, wrap seam),
// fast objects crossing many texels per step, tiny and large time steps.
#include <gtest/gtest.h>

#include <cstdio>

#include "physics_fixtures.hpp"

namespace thx::phys::test::test_hard_cases {
namespace {

const BodyMaterial kPlane{1.0, 0.0, 0.0}, kBall{0.5, 0.0, 0.0};

// Steps the world to t2; the ball's mean x acceleration between t1 and t2.
double accelBetween(PhysicsWorld& w, btRigidBody& ball, double dt, double t1, double t2) {
  double v1 = 0.0;
  const int n1 = int(std::lround(t1 / dt)), n2 = int(std::lround(t2 / dt));
  for (int k = 1; k <= n2; ++k) {
    w.step(dt);
    if (k == n1) v1 = velocityOf(ball).x();
  }
  return (velocityOf(ball).x() - v1) / (double(n2 - n1) * dt);
}

// Horizontal acceleration of a ball rolling on a tilted normal map between t1 and t2.
double rollingAccel(double angle_deg, double dt, double t1, double t2, double v0 = 0.0,
                    tex::Address address = tex::Address::Wrap, double x0 = 0.0) {
  SurfaceHolder s = holdSurface(tiltedMap(angle_deg, 64, 0.2), 0.2, false, address);
  PhysicsWorld w;
  w.addNormalMapPlane(s.surface, kPlane);
  btRigidBody& ball = w.addSphere(0.01, 0.05, at(x0, 0, 0.01), kBall);
  setRolling(ball, v0 * std::cos(deg(angle_deg)) / std::cos(deg(angle_deg)), 0.01);
  setVelocity(ball, {v0, 0, 0}, {0, v0 * std::cos(deg(angle_deg)) / 0.01, 0});
  return accelBetween(w, ball, dt, t1, t2);
}

TEST(TimeStep, TinyAndLargeStepsKeepTheRollingAcceleration) {
  const double expected = 5.0 / 7.0 * kG * std::tan(deg(5.0));
  const double tiny = rollingAccel(5.0, 1e-4, 0.05, 0.3);
  const double large = rollingAccel(5.0, 1.0 / 60.0, 0.1, 0.6);
  std::printf("[measured] a(dt=1e-4) = %.5f, a(dt=1/60) = %.5f, expected %.5f m/s^2\n", tiny, large, expected);
  EXPECT_NEAR(tiny, expected, 0.01 * expected);
  EXPECT_NEAR(large, expected, 0.01 * expected);
}

// Horizontal acceleration of a ball rolling down a tilted relief (real geometry) between t1 and t2.
double reliefRollingAccel(double angle_deg, double dt, double t1, double t2) {
  SurfaceHolder s = holdSurface(tiltedMap(angle_deg, 512, 0.2), 0.2, true);
  PhysicsWorld w;
  w.addReliefPlane(s.surface, kPlane);
  const double x0 = -0.08, z0 = -std::tan(deg(angle_deg)) * (x0 + 0.1 - 0.1 / 512) + 0.01 / std::cos(deg(angle_deg));
  btRigidBody& ball = w.addSphere(0.01, 0.05, at(x0, 0, z0), kBall);
  return accelBetween(w, ball, dt, t1, t2);
}

TEST(TimeStep, ReliefRollingAtTinyAndLargeSteps) {
  const double angle = 5.0;
  const double expected = 5.0 / 7.0 * kG * std::sin(deg(angle)) * std::cos(deg(angle));
  for (double dt : {1e-4, 1.0 / 60.0}) {
    const double a = reliefRollingAccel(angle, dt, 0.1, 0.3);
    std::printf("[measured] relief a(dt=%.5f) = %.5f, expected %.5f m/s^2\n", dt, a, expected);
    EXPECT_NEAR(a, expected, 0.01 * expected) << "dt " << dt;
  }
}

// The paper's rate (60 Hz) and ours (1 kHz), on both representations of the same 20° tilt. They
// differ by design: the normal-map contact holds the ball's height on the flat plane, so the tilted
// normal pushes it along the plane at 5/7 g tanθ; on the relief the ball descends a real slope and
// its horizontal acceleration is 5/7 g sinθ cosθ: a factor 1/cos²θ apart, 13 % at 20°
// (docs/physics.md, "Which tilt").
TEST(TimeStep, NormalMapAndReliefTiltsAt60And1000Hz) {
  const double angle = 20.0, t = std::tan(deg(angle));
  const double normal_expected = 5.0 / 7.0 * kG * t;
  const double relief_expected = 5.0 / 7.0 * kG * std::sin(deg(angle)) * std::cos(deg(angle));
  for (double dt : {1e-3, 1.0 / 60.0}) {
    const double normal = rollingAccel(angle, dt, 0.1, 0.4), relief = reliefRollingAccel(angle, dt, 0.1, 0.3);
    std::printf("[measured] 20 deg, dt %.5f: normal map %.4f (5/7 g tan = %.4f), relief %.4f (5/7 g sin cos = %.4f), "
                "ratio %.4f\n",
                dt, normal, normal_expected, relief, relief_expected, normal / relief);
    EXPECT_NEAR(normal, normal_expected, 0.01 * normal_expected) << "dt " << dt;
    EXPECT_NEAR(relief, relief_expected, 0.02 * relief_expected) << "dt " << dt;
    EXPECT_NEAR(normal / relief, 1.0 + t * t, 0.03);
  }
}

TEST(FastObjects, NormalMapRollingIsSpeedIndependent) {
  // 2 m/s = 2 mm per step, 0.6 texel per step here; the slope is uniform, so only the speed
  // dependent artefacts (sinking along n_s) could change the answer.
  const double expected = 5.0 / 7.0 * kG * std::tan(deg(5.0));
  const double a = rollingAccel(5.0, 1e-3, 0.05, 0.25, 2.0);
  EXPECT_NEAR(a, expected, 0.01 * expected);
}

double dimples(double x, double y) {
  // 3 mm radius, 0.3 mm deep caps every 1 cm (tiles a 0.1 m map).
  const double pitch = 0.01, a = 0.003, dep = 0.3e-3, big_r = (a * a + dep * dep) / (2.0 * dep);
  const double dx = x - (std::floor(x / pitch) + 0.5) * pitch, dy = y - (std::floor(y / pitch) + 0.5) * pitch;
  const double r2 = dx * dx + dy * dy;
  return r2 < a * a ? -(std::sqrt(big_r * big_r - r2) - (big_r - dep)) : 0.0;
}

TEST(FastObjects, FastBallOverADimpleFieldNeitherTunnelsNorGainsEnergy) {
  // 3 m/s at 1 kHz = 3 mm per step = 8 texels per step, across the wrap seam several times.
  SurfaceHolder s = holdSurface(heightMap(256, 0.1, dimples), 0.1, true);
  PhysicsWorld w;
  w.addReliefPlane(s.surface, kPlane);
  const double r = 0.005, m = 0.01, v0 = 3.0;
  btRigidBody& ball = w.addSphere(r, m, at(0.0, 0.005, r), kBall);  // along a row of dimple centres
  setRolling(ball, v0, r);
  const double inertia = 0.4 * m * r * r;
  auto energy = [&] {
    return 0.5 * m * velocityOf(ball).squaredNorm() + 0.5 * inertia * angularVelocityOf(ball).squaredNorm() +
           m * kG * positionOf(ball).z();
  };
  const double e0 = energy();
  double e_max = e0, z_min = 1.0;
  for (int k = 0; k < 300; ++k) {
    w.step(1e-3);
    e_max = std::max(e_max, energy());
    z_min = std::min(z_min, positionOf(ball).z());
  }
  std::printf("[measured] fast ball: E_max/E0 = %.4f, E_end/E0 = %.4f, z_min = %.6f m, x = %.4f m\n", e_max / e0,
              energy() / e0, z_min, positionOf(ball).x());
  EXPECT_GT(z_min, r - s.map->maxDepth()) << "never below a dimple's bottom";
  EXPECT_LT(e_max, 1.02 * e0) << "contacts inject no energy";
  EXPECT_GT(positionOf(ball).x(), 0.8 * v0 * 0.3) << "it keeps going";
}

// A 1 cm ball rolling at 3 m/s along a row of dimple centres of a normal map (no relief: the
// dimples exist only in the normals) for 0.3 s with time step dt. Returns (x, v_x) at the end.
Eigen::Vector2d fastOverNormalMapDimples(const SurfaceHolder& s, double dt) {
  PhysicsWorld w;
  w.addNormalMapPlane(s.surface, kPlane);
  const double r = 0.005, v0 = 3.0;
  btRigidBody& ball = w.addSphere(r, 0.01, at(0.0, 0.005, r), kBall);
  setRolling(ball, v0, r);
  const int n = int(std::lround(0.3 / dt));
  for (int k = 0; k < n; ++k) w.step(dt);
  return {positionOf(ball).x(), velocityOf(ball).x()};
}

TEST(FastObjects, NormalMapDimplesAtEightTexelsPerStepMatchASmallStepReference) {
  // 3 m/s at 1 kHz = 3 mm = 7.7 texels per step: each step samples the normal at one point of a
  // 3 mm path that crosses a 6 mm dimple in two steps. The reference steps 20× finer (0.4 texel
  // per step). The dimples speed the ball up and slow it down again; what the coarse step must
  // not do is lose or gain speed on average.
  SurfaceHolder s = holdSurface(heightMap(256, 0.1, dimples), 0.1, false);
  const Eigen::Vector2d coarse = fastOverNormalMapDimples(s, 1e-3), fine = fastOverNormalMapDimples(s, 5e-5);
  std::printf("[measured] normal-map dimples at 3 m/s: dt 1 ms x = %.4f m v = %.4f m/s; dt 0.05 ms x = %.4f m v = %.4f m/s\n",
              coarse.x(), coarse.y(), fine.x(), fine.y());
  EXPECT_NEAR(coarse.y(), fine.y(), 0.02 * fine.y());
  EXPECT_NEAR(coarse.x(), fine.x(), 0.02 * fine.x());
}

TEST(FastObjects, DropOntoTheReliefDoesNotPassThrough) {
  SurfaceHolder s = holdSurface(heightMap(256, 0.1, dimples), 0.1, true);
  PhysicsWorld w;
  w.addReliefPlane(s.surface, kPlane);
  const double r = 0.005;
  btRigidBody& ball = w.addSphere(r, 0.01, at(0.005, 0.005, 0.05), kBall);  // a dimple's centre below
  setVelocity(ball, {0, 0, -2.0}, {0, 0, 0});  // 2 mm per step, a 4th of the ball
  double z_min = 1.0;
  for (int k = 0; k < 500; ++k) {
    w.step(1e-3);
    z_min = std::min(z_min, positionOf(ball).z());
  }
  const double rest = r - s.map->maxDepth();  // the cap (1.5 cm radius) is wider than the ball
  // Discrete contacts: the impact step may overlap by up to one step's travel (2.2 mm here,
  // measured 1.2 mm); the next steps push it out.
  const double v_impact = std::sqrt(2.0 * 2.0 + 2.0 * kG * (0.05 - r));
  EXPECT_GT(z_min, rest - v_impact * 1e-3) << "overlaps by less than one step's travel on impact";
  EXPECT_NEAR(positionOf(ball).z(), rest, 1e-5) << "settles in the dimple";
  EXPECT_LT(velocityOf(ball).norm(), 1e-3);
}

TEST(TextureEdges, ClampedBorderContinuesTheEdgeNormals) {
  // The ball starts 1 cm inside the right edge at 0.5 m/s and leaves the texture; with clamp the
  // edge column's normal continues outward, so the acceleration does not change.
  const double expected = 5.0 / 7.0 * kG * std::tan(deg(5.0));
  const double a = rollingAccel(5.0, 1e-3, 0.05, 0.3, 0.5, tex::Address::Clamp, 0.09);
  EXPECT_NEAR(a, expected, 0.01 * expected);
}

// A 1 cm ball rolling at 0.4 m/s from x = 0.03 across sine ridges along x (0.2 mm high, 2 cm
// period, 5 periods over a 0.1 m relief of 256² texels) and over its border at x = 0.05, for
// `steps` ms after settling onto the ridges for 20 ms.
struct RidgeRun {
  double e0, e_max, e_end;  // mechanical energy after settling, its maximum, at the end (J)
  double dz_max;            // largest height change in one step (m)
  double x_end, v_end;      // where it ends, its speed along x
};
RidgeRun rollAcrossRidges(tex::Address address, int steps) {
  const double amp = 0.2e-3, period = 0.02;
  SurfaceHolder s = holdSurface(heightMap(256, 0.1, [&](double x, double) { return amp * std::sin(2 * kPi * x / period); },
                                          address),
                                0.1, true, address);
  PhysicsWorld w;
  w.addReliefPlane(s.surface, kPlane);
  const double r = 0.005, m = 0.01;
  btRigidBody& ball = w.addSphere(r, m, at(0.03, 0.0, r), kBall);
  setRolling(ball, 0.4, r);
  auto energy = [&] {
    return 0.5 * m * velocityOf(ball).squaredNorm() + 0.5 * 0.4 * m * r * r * angularVelocityOf(ball).squaredNorm() +
           m * kG * positionOf(ball).z();
  };
  for (int k = 0; k < 20; ++k) w.step(1e-3);
  RidgeRun run{energy(), energy(), 0.0, 0.0, 0.0, 0.0};
  double z_prev = positionOf(ball).z();
  for (int k = 0; k < steps; ++k) {
    w.step(1e-3);
    const double z = positionOf(ball).z();
    run.dz_max = std::max(run.dz_max, std::fabs(z - z_prev));
    z_prev = z;
    run.e_max = std::max(run.e_max, energy());
  }
  run.e_end = energy();
  run.x_end = positionOf(ball).x();
  run.v_end = velocityOf(ball).x();
  return run;
}

TEST(TextureEdges, ClampedReliefEdgeIsCrossedWithoutAJumpOrEnergyGain) {
  // Past a clamped relief's edge the edge depth continues, flat. A ball rolling out over the edge
  // keeps its energy and its height changes smoothly; it goes on rolling outside. (With the edge
  // texel's tilted normal continued too, it gained 19 % energy within 6 cm.)
  const RidgeRun r = rollAcrossRidges(tex::Address::Clamp, 150);
  std::printf("[measured] clamped relief edge: x = %.4f m, E_max/E0 = %.4f, E/E0 = %.4f, max |dz| per step = %.3g m\n",
              r.x_end, r.e_max / r.e0, r.e_end / r.e0, r.dz_max);
  ASSERT_GT(r.x_end, 0.06) << "left the texture";
  EXPECT_LT(r.e_max, 1.02 * r.e0) << "no energy gained at the edge";
  EXPECT_GT(r.e_end, 0.9 * r.e0) << "none lost there either";
  EXPECT_LT(r.dz_max, 4e-5) << "no height jump at the edge";
  EXPECT_GT(r.v_end, 0.3) << "it rolls on outside";
}

TEST(TextureEdges, WrapSeamIsSeamless) {
  // The periodic relief crossed through the wrap seam at x = 0.05: mechanical energy is kept and
  // the height does not jump there.
  const RidgeRun r = rollAcrossRidges(tex::Address::Wrap, 100);
  ASSERT_GT(r.x_end, 0.05) << "crossed the seam";
  std::printf("[measured] wrap seam: E/E0 = %.4f, max |dz| per step = %.3g m\n", r.e_end / r.e0, r.dz_max);
  EXPECT_NEAR(r.e_end, r.e0, 0.02 * r.e0);
  // The ball's height changes smoothly: at 0.4 m/s over 0.2 mm ridges the steepest slope is
  // 2 pi A / L = 0.063, so 0.4 mm/s * 0.063 * 1 ms = 25 µm per step at most.
  EXPECT_LT(r.dz_max, 4e-5);
}

// Horizontal acceleration (between 20 and 100 ms) and lowest centre height of a 1 cm ball on a
// normal map whose every stored normal is 89.9° from the plane's (TextureMap keeps z >= 1e-3).
struct GrazingRun {
  double a, a_z, z_min;  // a_z: mean vertical acceleration over the window (the height hold's bob)
};
GrazingRun grazingRun(double friction) {
  tex::TextureMap map(16, 16, tex::Representation::Normal);
  for (int j = 0; j < 16; ++j)
    for (int i = 0; i < 16; ++i) map.setNormal(i, j, Eigen::Vector3f(std::sin(float(deg(89.9))), 0.0f, std::cos(float(deg(89.9)))));
  SurfaceHolder s = holdSurface(std::move(map), 0.2, false);
  PhysicsWorld w;
  w.addNormalMapPlane(s.surface, {friction, 0, 0});
  btRigidBody& ball = w.addSphere(0.01, 0.05, at(0, 0, 0.01), {1.0, 0, 0});
  Eigen::Vector3d v1 = Eigen::Vector3d::Zero();
  double z_min = 1.0;
  for (int k = 1; k <= 100; ++k) {
    w.step(1e-3);
    z_min = std::min(z_min, positionOf(ball).z());
    if (k == 20) v1 = velocityOf(ball);
    EXPECT_TRUE(std::isfinite(positionOf(ball).x()));
  }
  const Eigen::Vector3d a = (velocityOf(ball) - v1) / 0.08;
  return {a.x(), a.z(), z_min};
}

TEST(GrazingNormals, ClampKeepsTheBallOnThePlane) {
  // The default clamp (75°) bounds the virtual slope: the ball accelerates as on that slope and
  // stays on the plane. On the slope's normal n and downhill tangent t, frictionless:
  // a_t = g sin θ; rolling (mu = 2 > 2/7 tan 75° = 1.07, so it does not slip): a_t = 5/7 g sin θ.
  // The height hold keeps the centre's height, so a_z is the hold's bob (the ball first sinks
  // ~0.9 mm, then is pushed back up), not the slope's: a_x = a_t / cos θ + a_z tan θ. Ignoring a_z
  // reads 4.5 % above g tan θ over this window.
  const double slope = std::tan(deg(75.0));
  const GrazingRun sliding = grazingRun(0.0), rolling = grazingRun(2.0);
  const double sliding_expected = slope * (kG + sliding.a_z), rolling_expected = slope * (5.0 / 7.0 * kG + rolling.a_z);
  std::printf("[measured] grazing: a = %.3f (expected %.3f; g tan 75° = %.3f), rolling a = %.3f (expected %.3f; "
              "5/7 g tan 75° = %.3f) m/s^2, a_z = %.3f / %.3f, z_min = %.5f / %.5f m\n",
              sliding.a, sliding_expected, kG * slope, rolling.a, rolling_expected, 5.0 / 7.0 * kG * slope, sliding.a_z,
              rolling.a_z, sliding.z_min, rolling.z_min);
  EXPECT_NEAR(sliding.a, sliding_expected, 0.01 * sliding_expected);
  EXPECT_NEAR(rolling.a, rolling_expected, 0.01 * rolling_expected);
  for (const GrazingRun& r : {sliding, rolling}) {
    EXPECT_LT(std::abs(r.a_z), 0.1 * kG) << "the bob stays small next to the slope's acceleration";
    EXPECT_GT(r.z_min, 0.01 - 2e-3) << "sinks by at most the documented artefact";
  }
}

TEST(GrazingNormals, ClampedNormalKeepsItsAzimuth) {
  tex::TextureMap map(4, 4, tex::Representation::Normal);
  const Eigen::Vector3f grazing(0.6f * 0.9999f, 0.8f * 0.9999f, std::sqrt(1.0f - 0.9999f * 0.9999f));
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) map.setNormal(i, j, grazing);
  SurfaceHolder s = holdSurface(std::move(map), 0.2, false);
  const Eigen::Vector3d n = clampedSampledNormal(s.surface, 0.0, 0.0, 60.0);
  EXPECT_NEAR(n.norm(), 1.0, 1e-12);
  EXPECT_NEAR(n.z(), 0.5, 1e-12);
  EXPECT_NEAR(n.y() / n.x(), 0.8 / 0.6, 1e-4);  // snorm16 storage of a grazing normal
  const Eigen::Vector3d untouched = clampedSampledNormal(s.surface, 0.0, 0.0, 90.0);
  EXPECT_NEAR(untouched.z(), double(grazing.z()), 1e-3);
}

}  // namespace
}  // namespace thx::phys::test::test_hard_cases
