#pragma once
// The analytic rolling scenes on tessellated spheres (issue 29), shared by
// tests/physics/test_mesh_rolling.cpp (which holds them to the answers) and
// benchmarks/bench_physics_mesh.cpp (which measures their error and cost against the
// tessellation): a ball swinging inside a sphere (a bowl) and a ball rolling off its top.
#include <BulletCollision/NarrowPhaseCollision/btPersistentManifold.h>

#include <Eigen/Geometry>
#include <chrono>
#include <cmath>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include "clients/physics/bullet_convert.hpp"
#include "clients/physics/physics_world.hpp"
#include "meshes/mesh_generators.hpp"
#include "tests/physics/physics_fixtures.hpp"
#include "textures/ball_on_relief.hpp"
#include "textures/height_from_normals.hpp"

namespace thx::phys::test::mesh_rolling {

inline constexpr double kBallRadius = 0.01, kBallMass = 0.05, kDt = 1e-3;

inline Eigen::Isometry3d placedAt(const Eigen::Vector3d& p) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.translation() = p;
  return t;
}

// Sum of the normal impulses the last step applied between `ball` and anything.
inline double normalImpulse(PhysicsWorld& w, const btRigidBody& ball) {
  double total = 0.0;
  btDispatcher* d = w.world().getDispatcher();
  for (int m = 0; m < d->getNumManifolds(); ++m) {
    const btPersistentManifold* manifold = d->getManifoldByIndexInternal(m);
    if (manifold->getBody0() != &ball && manifold->getBody1() != &ball) continue;
    for (int k = 0; k < manifold->getNumContacts(); ++k) total += double(manifold->getContactPoint(k).m_appliedImpulse);
  }
  return total;
}

// A UV sphere mesh of `radius` (`segments` around, half as many rings) at the origin, turned by
// `turn` (the sphere's frame to the world's), in a world. With `texture`, the map is laid at one
// tile per kTileM of arc (its normals made for that tile), read at one point under a ball, or
// with `ball_relief` (built from it) as the ball's sphere meets the relief: the steered ball,
// held on the smooth surface (MeshContactOptions::lift_ball false), whose swing the rolling model
// of slope_predicted_swing.hpp integrates; the product's lifted ball loses energy where its
// contact jumps across a trough, held to the rolling-impact law in test_relief_mesh_ridges.cpp.
inline constexpr double kTileM = 0.01;
struct SphereScene {
  mesh::GeneratedMesh sphere;
  PhysicsWorld world;
  SphereScene(int segments, bool smooth, double radius, const tex::TextureMap* texture = nullptr,
              const Eigen::Matrix3d& turn = Eigen::Matrix3d::Identity(), const tex::BallOnRelief* ball_relief = nullptr,
              bool lift_ball = false)
      : sphere(mesh::sphere(radius, segments, segments / 2, kTileM)) {
    MeshContactOptions options;
    options.smooth = smooth;
    options.texture = texture;
    options.ball_relief = ball_relief;
    options.lift_ball = lift_ball;
    options.normals_made_for_m = Eigen::Vector2d::Constant(kTileM);
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.linear() = turn;
    world.addTexturedMesh(sphere.mesh, pose, {1.0, 0.0, 0.0}, options);
  }
};

// Unturned, the bowl's bottom is the UV sphere's south pole, where u closes to a point: there the
// uv squeezes a texture along u (its bumps a fraction of a millimetre apart and, rescaled to the
// tile they were made for, many times steeper). This turn puts the bottom on the equator instead,
// where the texture lies at its stated scale, and about an eighth of the sine bumps' period off
// their node lines (kTileM / 32 of arc along v), so the swing along u meets their slopes both
// along and across its path.
inline Eigen::Matrix3d bottomOnTheEquator(double bowl_radius) {
  return Eigen::AngleAxisd(0.5 * kPi + kTileM / 32.0 / bowl_radius, Eigen::Vector3d::UnitX()).toRotationMatrix();
}

// Sine bumps (textures/generators/sine.cpp) of period kTileM / 4 whose steepest slope is `slope`
// (amplitude x 2 pi / period), one tile of 256 texels.
inline tex::TextureMap sineBumps(double slope) {
  tex::GenerateRequest r;
  r.kind = "sine";
  r.size = 256;
  const double period = kTileM / 4.0;
  r.params = {{"amplitude", slope * period / (2.0 * kPi)}, {"period", period}, {"extent", kTileM}};
  return tex::generate(r);
}

// Their crests' curvature, a k^2 = s k (both ways at a crest; the most anywhere on them).
inline double sineBumpsCrestCurvature(double slope) { return slope * 2.0 * kPi / (kTileM / 4.0); }

// A normal map (no depth) as physics-client gives it to a ball on a mesh (MeshGround): the relief
// its normals integrate to (textures/height_from_normals.hpp), lifted onto, and their mean slope,
// which a periodic relief cannot hold.
struct NormalMapRelief {
  tex::TextureMap normals;  // the map's normals alone, no depth
  tex::TextureMap relief;
  Eigen::Vector2d mean_slope;
  std::optional<tex::BallOnRelief> ball;
};
inline std::unique_ptr<NormalMapRelief> normalMapRelief(const tex::TextureMap& map, double tile_m) {
  auto r = std::make_unique<NormalMapRelief>();
  r->normals = tex::TextureMap(map.width(), map.height(), tex::Representation::Normal);
  for (int j = 0; j < map.height(); ++j)
    for (int i = 0; i < map.width(); ++i) r->normals.setNormal(i, j, map.normal(i, j));
  tex::ReliefOfNormals integrated = tex::reliefFromNormals(r->normals, Eigen::Vector2d::Constant(tile_m), tex::Address::Wrap);
  r->relief = std::move(integrated.relief);
  r->mean_slope = integrated.mean_slope;
  r->ball.emplace(r->relief, tex::Address::Wrap);
  return r;
}

struct Swing {
  double period_s = 0.0;
  int periods = 0;
  double us_per_step = 0.0;  // wall clock, the whole step
  double end_amplitude_m = 0.0;  // the largest distance from the bottom along the swing in the last second
};

// The ball released at rest theta_0 up the inside of a sphere of radius R (the bowl), along +x of
// the world, for `seconds` of steps of `dt`; the period from the times it crosses the bottom
// moving in +x.
inline Swing swingInBowl(int segments, bool smooth, double bowl_radius, double theta0_deg, double seconds,
                         const tex::TextureMap* texture = nullptr, const Eigen::Matrix3d& turn = Eigen::Matrix3d::Identity(),
                         const tex::BallOnRelief* ball_relief = nullptr, double dt = kDt, bool lift_ball = false) {
  SphereScene scene(segments, smooth, bowl_radius, texture, turn, ball_relief, lift_ball);
  PhysicsWorld& w = scene.world;
  const double l = bowl_radius - kBallRadius, th = deg(theta0_deg);
  btRigidBody& ball = w.addSphere(kBallRadius, kBallMass, placedAt({l * std::sin(th), 0.0, -l * std::cos(th)}),
                                  {1.0, 0.0, 0.0});
  std::vector<double> crossings;
  double x_last = positionOf(ball).x();
  const int steps = int(std::lround(seconds / dt));
  const auto start = std::chrono::steady_clock::now();
  double end_amplitude = 0.0;
  for (int k = 1; k <= steps; ++k) {
    w.step(dt);
    const double x = positionOf(ball).x();
    if (x_last < 0.0 && x >= 0.0) crossings.push_back(dt * (k - 1 + (-x_last) / (x - x_last)));
    x_last = x;
    if (double(steps - k) * dt < 1.0) end_amplitude = std::max(end_amplitude, std::fabs(x));
  }
  Swing s;
  s.end_amplitude_m = end_amplitude;
  s.us_per_step = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count() / steps;
  s.periods = int(crossings.size()) - 1;
  if (s.periods > 0) s.period_s = (crossings.back() - crossings.front()) / s.periods;
  return s;
}

struct Departure {
  double theta_deg = 0.0;  // from the top, where the normal impulse first vanished
  bool left = false;
};

// With `ball_relief`, the texture's relief met as the ball's sphere meets it (lifted onto it with
// `lift_ball`, the product's default; steered otherwise), as in swingInBowl.
inline Departure rollOffSphere(int segments, bool smooth, double sphere_radius, double theta0_deg, double friction,
                               const tex::TextureMap* texture = nullptr, const tex::BallOnRelief* ball_relief = nullptr,
                               bool lift_ball = false, double dt = kDt) {
  SphereScene scene(segments, smooth, sphere_radius, texture, Eigen::Matrix3d::Identity(), ball_relief, lift_ball);
  PhysicsWorld& w = scene.world;
  const double l = sphere_radius + kBallRadius, th = deg(theta0_deg);
  // Off the x axis by a little so the ball does not roll along one ring of vertices.
  const Eigen::Vector3d dir = Eigen::Vector3d(std::cos(0.3), std::sin(0.3), 0.0);
  btRigidBody& ball = w.addSphere(kBallRadius, kBallMass, placedAt(l * (std::sin(th) * dir + std::cos(th) * Eigen::Vector3d::UnitZ())),
                                  {friction, 0.0, 0.0});
  // The last step that pushed the ball is where it left (it may lift off a facet's edge for a
  // step before that and land again).
  Departure d;
  const int steps = int(std::lround(3.0 / dt));
  for (int k = 1; k <= steps; ++k) {
    w.step(dt);
    const Eigen::Vector3d c = positionOf(ball);
    const double theta = std::atan2(std::hypot(c.x(), c.y()), c.z()) * 180.0 / kPi;
    if (normalImpulse(w, ball) > 0.0) {
      d.theta_deg = theta;
      d.left = false;
    } else if (theta > 90.0) {
      d.left = true;
      break;
    }
  }
  return d;
}

// The exact answers.
inline double swingPeriod(double bowl_radius) { return 2.0 * kPi * std::sqrt(7.0 * (bowl_radius - kBallRadius) / (5.0 * kG)); }
// At a swing of theta_0 (rad): the pendulum's series, T0 (1 + theta_0^2 / 16 + 11 theta_0^4 / 3072);
// the next term is below 1e-8 of T0 at 5 degrees.
inline double swingPeriodAt(double bowl_radius, double theta0_deg) {
  const double t2 = deg(theta0_deg) * deg(theta0_deg);
  return swingPeriod(bowl_radius) * (1.0 + t2 / 16.0 + 11.0 * t2 * t2 / 3072.0);
}
inline double departureDeg(double theta0_deg) {
  return std::acos(10.0 / 17.0 * std::cos(theta0_deg * kPi / 180.0)) * 180.0 / kPi;
}
// Where a rigid ball rolling from rest theta_0 off the top of a sphere (its centre on radius
// l = R + r) leaves it if its centre's path there curves by 1/l plus `path_curvature` (1/m): where
// gravity's pull along the normal no longer holds it on that path, v^2 (1/l + path_curvature) =
// g cos(theta), with v^2 = 10/7 g l (cos(theta_0) - cos(theta)) from the energy of rolling (a
// texture's own heights left out: under 1e-3 of l's here). Zero: departureDeg.
inline double departureOnPathDeg(double sphere_radius, double theta0_deg, double path_curvature) {
  const double a = 10.0 / 7.0 * (1.0 + path_curvature * (sphere_radius + kBallRadius));
  if (!(a > 0.0)) return NAN;  // held at any speed
  return std::acos(a * std::cos(theta0_deg * kPi / 180.0) / (1.0 + a)) * 180.0 / kPi;
}
// Bumps on the sphere bound where it leaves. The earliest: at a crest of curvature kappa (a k^2 at
// the top of sine bumps a sin(kx) sin(ky)) its centre's path, riding it, curves by
// kappa / (1 + r kappa) more.
inline double earliestDepartureOverCrestsDeg(double sphere_radius, double theta0_deg, double crest_curvature) {
  return departureOnPathDeg(sphere_radius, theta0_deg, crest_curvature / (1.0 + kBallRadius * crest_curvature));
}
// The latest it can leave: in a trough of that curvature its centre's path curves back by
// kappa / (1 - r kappa); NAN where no speed lifts it out of one (that path curves back more than
// the sphere curves on) or where the ball bridges the trough (r kappa >= 1: held by two touches).
inline double latestDepartureInTroughsDeg(double sphere_radius, double theta0_deg, double trough_curvature) {
  if (kBallRadius * trough_curvature >= 1.0) return NAN;
  return departureOnPathDeg(sphere_radius, theta0_deg, -trough_curvature / (1.0 - kBallRadius * trough_curvature));
}

}  // namespace thx::phys::test::mesh_rolling
