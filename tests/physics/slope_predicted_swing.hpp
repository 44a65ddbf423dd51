#pragma once
// What a texture's own slopes predict for the ball swinging in the bowl (issue 29: "the same
// scenes with a fine texture change the mean by less than the texture's own slope predicts").
//
// The prediction leaves Bullet out and keeps only what the texture says: the ball's centre held
// on the smooth sphere of radius R - r, pulled by gravity and pushed by the contact force along
// the normal the texture tilts at the foot of the centre, rolling without slipping (a force
// through the centre accelerates it at 5/7 of force / mass), integrated by RK4 at 0.1 ms. The
// texture is read through the product's own lookup on the same mesh (smoothFoot and
// meshContactNormal at one point, or ballOnReliefNormal as the ball meets a relief), so the
// prediction and the simulation read the same slopes;
// only the mechanics differ: no solver, no 1 ms step, no tessellated gap. Untextured it is the
// exact swing, a pendulum's of length 7 (R - r) / 5 (swingPeriodAt).
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "clients/physics/mesh_contact.hpp"
#include "tests/physics/mesh_rolling_scenes.hpp"

namespace thx::phys::test::mesh_rolling {

// The slope the texture adds at ball centre c inside `sphere` (towards the ball): the steered
// normal's part along the smooth surface over its part across it, turned onto the exact sphere's
// tangent plane there. `triangle` and `b` carry the foot from call to call.
struct SlopeAtFoot {
  const ContactMesh& contact_mesh;
  MeshContactOptions options;
  std::uint32_t triangle = 0;
  Eigen::Vector3d b = Eigen::Vector3d::Constant(1.0 / 3.0);

  Eigen::Vector3d operator()(const Eigen::Vector3d& c) {
    smoothFoot(contact_mesh, c, -1.0, triangle, b);
    const mesh::SurfaceFrame f = mesh::frameAt(*contact_mesh.mesh, triangle, b, mesh::FrameMode::Interpolated);
    const Eigen::Vector3d smooth = -f.normal;
    const Eigen::Vector3d n = options.texture && options.ball_relief
                                  ? ballOnReliefNormal(contact_mesh, c, -1.0, triangle, b, kBallRadius, options)
                                  : Eigen::Vector3d(-meshContactNormal(*contact_mesh.mesh, triangle, b, options));
    const Eigen::Vector3d slope = (n - n.dot(smooth) * smooth) / n.dot(smooth);
    const Eigen::Vector3d up = -c.normalized();  // the exact sphere's normal towards the ball
    return slope - slope.dot(up) * up;
  }
};

// The swing of swingInBowl (the same release, sphere and turn, the same crossings counted) as the
// texture's slopes predict it.
inline Swing slopePredictedSwing(int segments, double bowl_radius, double theta0_deg, double seconds,
                                 const tex::TextureMap* texture,
                                 const Eigen::Matrix3d& turn = Eigen::Matrix3d::Identity(),
                                 const tex::BallOnRelief* ball_relief = nullptr, double dt = 1e-4) {
  const mesh::GeneratedMesh sphere = mesh::sphere(bowl_radius, segments, segments / 2, kTileM);
  const ContactMesh contact_mesh(sphere.mesh);
  MeshContactOptions options;
  options.texture = texture;
  options.ball_relief = ball_relief;
  options.normals_made_for_m = Eigen::Vector2d::Constant(kTileM);
  const double l = bowl_radius - kBallRadius, th = deg(theta0_deg);
  // In the sphere's own frame: the world turned back.
  Eigen::Vector3d c = turn.transpose() * Eigen::Vector3d(l * std::sin(th), 0.0, -l * std::cos(th)), v = Eigen::Vector3d::Zero();
  SlopeAtFoot slope_at{contact_mesh, options, mesh::nearestTriangle(sphere.mesh, c * (bowl_radius / l))};
  const Eigen::Vector3d g = turn.transpose() * Eigen::Vector3d(0.0, 0.0, -kG), along = turn.transpose().col(0);
  auto accel = [&](const Eigen::Vector3d& p, const Eigen::Vector3d& u) -> Eigen::Vector3d {
    const Eigen::Vector3d up = -p.normalized();
    const double load = u.squaredNorm() / l - g.dot(up);  // normal force / mass along the smooth normal
    const Eigen::Vector3d pull = g - g.dot(up) * up + load * slope_at(p);
    return 5.0 / 7.0 * pull + u.squaredNorm() / l * up;
  };
  std::vector<double> crossings;
  double end_amplitude = 0.0;
  const long steps = std::lround(seconds / dt);
  for (long k = 1; k <= steps; ++k) {
    const Eigen::Vector3d a1 = accel(c, v), v1 = v;
    const Eigen::Vector3d v2 = v + 0.5 * dt * a1, a2 = accel(c + 0.5 * dt * v1, v2);
    const Eigen::Vector3d v3 = v + 0.5 * dt * a2, a3 = accel(c + 0.5 * dt * v2, v3);
    const Eigen::Vector3d v4 = v + dt * a3, a4 = accel(c + dt * v3, v4);
    const double x_last = c.dot(along);
    c += dt / 6.0 * (v1 + 2.0 * v2 + 2.0 * v3 + v4);
    v += dt / 6.0 * (a1 + 2.0 * a2 + 2.0 * a3 + a4);
    // Back onto the sphere, the velocity along it (RK4 drifts off by dt^5).
    c *= l / c.norm();
    v -= v.dot(c) / (l * l) * c;
    const double x = c.dot(along);
    if (x_last < 0.0 && x >= 0.0) crossings.push_back(dt * (double(k - 1) + (-x_last) / (x - x_last)));
    if (double(steps - k) * dt < 1.0) end_amplitude = std::max(end_amplitude, std::fabs(x));
  }
  Swing s;
  s.end_amplitude_m = end_amplitude;
  s.periods = int(crossings.size()) - 1;
  if (s.periods > 0) s.period_s = (crossings.back() - crossings.front()) / s.periods;
  return s;
}


// The lifted ball's swing (MeshContactOptions::lift_ball, the product's default) as a rigid ball
// rolling without slipping on the relief as its sphere meets it: its centre rides the lifted
// surface |c| = l - lift(c) (ballOnReliefLift: the relief dilated by the ball), rolling (7/10 v^2
// of kinetic energy per unit mass) with its energy kept while its touch moves continuously, and
// where the touch jumps across a trough sharper than the ball, the rolling-impact law of
// rolling_over_ridges.hpp: v' = v (2 + 5 cos phi) / 7, phi the angle between the two touches'
// normals. Integrated at `dt`: each step moves the centre by its velocity and gravity's pull along
// the surface (5/7 of it), puts it back onto the lifted surface, turns the velocity into the new
// tangent plane and sets its length from the energy.
inline constexpr double kTouchJumpRad = 0.02;
struct LiftedTouch {
  Eigen::Vector3d normal;  // the touch's, mesh frame, towards the ball
  double lift_m = 0.0;
};
inline LiftedTouch liftedTouch(const ContactMesh& contact_mesh, const MeshContactOptions& options, const Eigen::Vector3d& c,
                               std::uint32_t& triangle) {
  Eigen::Vector3d b = Eigen::Vector3d::Constant(1.0 / 3.0);
  smoothFoot(contact_mesh, c, -1.0, triangle, b);
  const mesh::SurfaceFrame f = mesh::frameAt(*contact_mesh.mesh, triangle, b, mesh::FrameMode::Interpolated);
  const tex::BallOnRelief::Touch t =
      options.ball_relief->touch({f.uv.x(), f.uv.y()}, metresPerUvAt(contact_mesh, triangle, b), kBallRadius, true);
  // Tangent space (x along u, y along v, z out of the relief) to the mesh frame, met from behind.
  const Eigen::Vector3d e1 = (f.tangent - f.tangent.dot(f.normal) * f.normal).normalized();
  const Eigen::Vector3d e2 = f.normal.cross(e1);
  return {(t.normal.x() * e1 + t.normal.y() * e2 + t.normal.z() * f.normal).normalized(), t.lift_m};
}

inline Swing liftedPredictedSwing(int segments, double bowl_radius, double theta0_deg, double seconds,
                                  const tex::TextureMap& texture, const tex::BallOnRelief& ball_relief,
                                  const Eigen::Matrix3d& turn = Eigen::Matrix3d::Identity(), double dt = 1e-4,
                                  double* speed_kept = nullptr) {
  const mesh::GeneratedMesh sphere = mesh::sphere(bowl_radius, segments, segments / 2, kTileM);
  const ContactMesh contact_mesh(sphere.mesh);
  MeshContactOptions options;
  options.texture = &texture;
  options.ball_relief = &ball_relief;
  options.normals_made_for_m = Eigen::Vector2d::Constant(kTileM);
  const double l = bowl_radius - kBallRadius, th = deg(theta0_deg);
  Eigen::Vector3d c = turn.transpose() * Eigen::Vector3d(l * std::sin(th), 0.0, -l * std::cos(th));
  std::uint32_t triangle = mesh::nearestTriangle(sphere.mesh, c * (bowl_radius / l));
  std::uint32_t steer_triangle = triangle;
  const Eigen::Vector3d g = turn.transpose() * Eigen::Vector3d(0.0, 0.0, -kG), along = turn.transpose().col(0);
  // Onto the lifted surface along the sphere's radius (the lift read where the centre lands).
  auto lifted = [&](Eigen::Vector3d p) {
    for (int k = 0; k < 3; ++k) p *= (l - liftedTouch(contact_mesh, options, p, triangle).lift_m) / p.norm();
    return p;
  };
  // The lifted surface's normal towards the ball: the lift's gradient, as the contact steers it.
  auto normalAt = [&](const Eigen::Vector3d& p) {
    Eigen::Vector3d b = Eigen::Vector3d::Constant(1.0 / 3.0);
    smoothFoot(contact_mesh, p, -1.0, steer_triangle, b);
    return ballOnReliefNormal(contact_mesh, p, -1.0, steer_triangle, b, kBallRadius, options);
  };
  c = lifted(c);
  Eigen::Vector3d v = Eigen::Vector3d::Zero(), n = normalAt(c);
  Eigen::Vector3d touch = liftedTouch(contact_mesh, options, c, triangle).normal;
  double energy = -g.dot(c);  // per unit mass: 7/10 v^2 - g . c
  double kept = 1.0;
  std::vector<double> crossings;
  double end_amplitude = 0.0;
  const long steps = std::lround(seconds / dt);
  for (long k = 1; k <= steps; ++k) {
    const Eigen::Vector3d pull = 5.0 / 7.0 * (g - g.dot(n) * n);
    const double x_last = c.dot(along);
    c = lifted(c + dt * v + 0.5 * dt * dt * pull);
    const Eigen::Vector3d n_next = normalAt(c);
    v += dt * pull;
    v -= v.dot(n_next) * n_next;
    // The touch jumped (its normal turned by far more than rolling over a crest turns it, v dt / r:
    // 7e-4 rad at 69 mm/s, the top speed of a 5 degree swing, in a 0.1 ms step): held at both
    // places for an instant, it rolls on about the new one.
    const LiftedTouch t = liftedTouch(contact_mesh, options, c, triangle);
    const double phi = std::acos(std::clamp(t.normal.dot(touch), -1.0, 1.0));
    const double speed2 = std::max(0.0, (energy + g.dot(c)) / 0.7);
    if (phi > kTouchJumpRad) {
      const double f = (2.0 + 5.0 * std::cos(phi)) / 7.0;
      energy = 0.7 * f * f * speed2 - g.dot(c);
      kept *= f;
    }
    const double speed = std::sqrt(std::max(0.0, (energy + g.dot(c)) / 0.7));
    v = v.norm() > 0.0 ? Eigen::Vector3d(v.normalized() * speed) : v;
    n = n_next;
    touch = t.normal;
    const double x = c.dot(along);
    if (x_last < 0.0 && x >= 0.0) crossings.push_back(dt * (double(k - 1) + (-x_last) / (x - x_last)));
    if (double(steps - k) * dt < 1.0) end_amplitude = std::max(end_amplitude, std::fabs(x));
  }
  if (speed_kept) *speed_kept = kept;
  Swing s;
  s.end_amplitude_m = end_amplitude;
  s.periods = int(crossings.size()) - 1;
  if (s.periods > 0) s.period_s = (crossings.back() - crossings.front()) / s.periods;
  return s;
}

}  // namespace thx::phys::test::mesh_rolling
