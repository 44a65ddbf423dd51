#include "clients/study/ball_percept.hpp"

#include <algorithm>
#include <cmath>

#include "clients/physics_client/physics_scene.hpp"

namespace thx::study {

std::optional<BallPercept> watchBall(const scene::Scene& scene) {
  int ball = -1;
  for (std::size_t i = 0; i < scene.objects.size() && ball < 0; ++i)
    if (!scene.objects[i].fixed) ball = int(i);
  if (ball < 0) return std::nullopt;

  physclient::PhysicsScene sim(scene);  // the pen stays parked above the plane: it touches nothing
  const double dt = 1.0 / double(std::max(1, scene.rates.physics_hz));
  const long steps = long(std::ceil(kBallWatchS / dt));
  // The first 50 ms are the drop onto the surface (the scenes start the ball just above it):
  // its landing is an impact, not the texture's.
  const long settle = long(std::ceil(0.05 / dt));
  Eigen::Vector3d v_prev = sim.body(ball).v_world;
  Eigen::Vector3d sum_a = Eigen::Vector3d::Zero();
  double sum_a2 = 0.0, sum_slip = 0.0;
  long samples = 0, contact_samples = 0;
  for (long k = 0; k < steps; ++k) {
    sim.step(dt);
    const physclient::BodyState b = sim.body(ball);
    const Eigen::Vector3d a = (b.v_world - v_prev) / dt;
    v_prev = b.v_world;
    for (const physclient::LastingContact& c : sim.takeContacts()) {
      if (k < settle || c.body_a != ball || c.body_b != physclient::kBodySurface) continue;
      const double speed = b.v_world.norm();
      if (speed > 1e-3) sum_slip += std::min(1.0, c.v_slip_world.norm() / speed), ++contact_samples;
    }
    if (k < settle) continue;
    sum_a += a;
    sum_a2 += a.squaredNorm();
    ++samples;
  }
  if (samples == 0 || contact_samples == 0) return std::nullopt;  // it never rolled on the surface
  BallPercept p;
  const Eigen::Vector3d mean_a = sum_a / double(samples);
  const double var = std::max(0.0, sum_a2 / double(samples) - mean_a.squaredNorm());
  p.shake_log10 = std::log10(std::max(1e-4, std::sqrt(var) / 9.81));
  p.slip = sum_slip / double(contact_samples);
  p.watched_s = double(steps) * dt;
  return p;
}

}  // namespace thx::study
