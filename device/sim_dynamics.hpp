#pragma once
// Continuous-time part of the simulated PHANToM: one rigid body (pen + the hand holding it) pushed
// by the motors, the hand, the mechanism's viscous damping and its (smoothed) Coulomb friction.
//
// Integrator: semi-implicit (symplectic) Euler, v += a dt then x += v dt, at >= 10 kHz. Chosen
// because it neither adds nor removes energy from an undamped spring-mass on average: implicit
// Euler would damp oscillations numerically and hide the servo's sampled-data instability;
// explicit Euler would pump energy (x(1 + w^2 dt^2) per step) and make stable walls look
// unstable. Whatever instability shows therefore comes from the 1 kHz zero-order hold,
// quantisation and finite differences, as on a real device. Stable for w dt < 2; config
// validation keeps w dt <= 0.5 for the hand and the viscous terms.
//
// Real-time safe: no allocation, no exceptions.
#include <Eigen/Core>

#include "device/hand_script.hpp"
#include "device/sim_config.hpp"

namespace thx::dev {

struct SimBodyState {
  Eigen::Vector3d x_m = Eigen::Vector3d::Zero();  // pen tip, world
  Eigen::Vector3d v_m_per_s = Eigen::Vector3d::Zero();
};

class SimDynamics {
 public:
  explicit SimDynamics(const SimPhantomConfig& config);

  double massKg() const { return mass_kg_; }
  double dtS() const { return dt_s_; }

  // F_hand = k_h (x_target - x) + b_h (v_target - v) + push (the push is along -normal); while
  // pushing, the spring's component along the push is scaled down (SimPhantomConfig).
  Eigen::Vector3d handForce(const SimBodyState& s, const HandTarget& target_world) const;
  // Mechanism: -b v - F_c tanh(|v| / scale) v / |v|.
  Eigen::Vector3d mechanismForce(const Eigen::Vector3d& v_m_per_s) const;
  // One step with the motor force held; returns the motor's work on the body, F . dx.
  double step(SimBodyState& s, const Eigen::Vector3d& motor_n, const HandTarget& target_world) const;

 private:
  double mass_kg_;
  double dt_s_;
  double damping_ns_per_m_;
  double friction_n_;
  double friction_scale_m_per_s_;
  double hand_k_n_per_m_;
  double hand_b_ns_per_m_;
  double push_normal_fraction_;
};

}  // namespace thx::dev
