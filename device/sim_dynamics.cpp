#include "device/sim_dynamics.hpp"

#include <cmath>

namespace thx::dev {

SimDynamics::SimDynamics(const SimPhantomConfig& c)
    : mass_kg_(c.device_mass_kg + c.hand_mass_kg),
      dt_s_(1.0 / c.integration_hz),
      damping_ns_per_m_(c.spec.physical_damping_ns_per_m),
      friction_n_(c.friction_n),
      friction_scale_m_per_s_(c.friction_velocity_scale_m_per_s),
      hand_k_n_per_m_(c.hand_stiffness_n_per_m),
      hand_b_ns_per_m_(c.hand_damping_ns_per_m),
      push_normal_fraction_(c.hand_push_normal_stiffness_fraction) {}

Eigen::Vector3d SimDynamics::handForce(const SimBodyState& s, const HandTarget& t) const {
  Eigen::Vector3d spring = hand_k_n_per_m_ * (t.p_m - s.x_m);
  const double push_n = t.push_n.norm();
  if (push_n > 0.0) {
    constexpr double kBlendN = 0.2;  // the switch to force control completes over this much push
    const Eigen::Vector3d along = t.push_n / push_n;
    const double w = std::fmin(1.0, push_n / kBlendN) * (1.0 - push_normal_fraction_);
    spring -= w * along.dot(spring) * along;
  }
  return spring + hand_b_ns_per_m_ * (t.v_m_per_s - s.v_m_per_s) + t.push_n;
}

Eigen::Vector3d SimDynamics::mechanismForce(const Eigen::Vector3d& v) const {
  Eigen::Vector3d f = -damping_ns_per_m_ * v;
  const double speed = v.norm();
  // tanh(s / scale) / s -> 1 / scale as s -> 0: finite, and exactly zero force at rest.
  if (speed > 0.0) f -= (friction_n_ * std::tanh(speed / friction_scale_m_per_s_) / speed) * v;
  return f;
}

double SimDynamics::step(SimBodyState& s, const Eigen::Vector3d& motor_n, const HandTarget& target_world) const {
  const Eigen::Vector3d force = motor_n + handForce(s, target_world) + mechanismForce(s.v_m_per_s);
  s.v_m_per_s += (dt_s_ / mass_kg_) * force;
  const Eigen::Vector3d dx = dt_s_ * s.v_m_per_s;
  s.x_m += dx;
  return motor_n.dot(dx);
}

}  // namespace thx::dev
