#include "server/passivity.hpp"

#include "base/number_text.hpp"
#include "base/error.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace thx::srv {
namespace {

[[noreturn]] void reject(const char* field, double value, const char* expected) {
  throw thx::Error(thx::Error::Kind::Config, std::string("passivity config: ") + field + " = " + numberText(value) +
                              ": expected " + expected);
}

void requireNonNegative(const char* field, double value, const char* expected) {
  if (!std::isfinite(value) || value < 0.0) reject(field, value, expected);
}

}  // namespace

PassivityConfig PassivityConfig::fromSpec(const dev::DeviceSpec& spec, double period_s,
                                          double rendered_stiffness_n_per_m) {
  PassivityConfig c;
  c.period_s = period_s;
  c.max_damping_ns_per_m = spec.max_damping_ns_per_m;
  c.max_force_n = spec.continuous_force_n;
  c.stored_energy_stiffness_n_per_m = rendered_stiffness_n_per_m;
  try {
    c.validate();
  } catch (const thx::Error& e) {
    throw thx::Error(thx::Error::Kind::Config, "device model '" + spec.model + "': " + e.what());
  }
  return c;
}

void PassivityConfig::validate() const {
  if (!std::isfinite(period_s) || period_s < 1e-6 || period_s > 1.0) {
    reject("period_s", period_s, "a servo period in [1e-6, 1] s");
  }
  requireNonNegative("max_damping_ns_per_m", max_damping_ns_per_m, "a finite number >= 0 N s/m");
  requireNonNegative("max_force_n", max_force_n, "a finite number >= 0 N");
  requireNonNegative("max_reservoir_j", max_reservoir_j, "a finite energy >= 0 J");
  requireNonNegative("quantisation_play_m", quantisation_play_m, "a finite length >= 0 m");
  requireNonNegative("stored_energy_stiffness_n_per_m", stored_energy_stiffness_n_per_m,
                     "a finite stiffness >= 0 N/m (0: the environment stores no energy)");
  if (output_delay_ticks < 0 || output_delay_ticks > kMaxOutputDelayTicks) {
    reject("output_delay_ticks", output_delay_ticks, "a tick count in [0, 3]");
  }
}

PassivityController::PassivityController(const PassivityConfig& config) : config_(config) {
  config_.validate();
  enabled_ = config_.enabled;
  slots_ = config_.output_delay_ticks + 1;
}

void PassivityController::reset() {
  in_flight_.fill(InFlight{});
  oldest_ = 0;
  observed_j_ = 0.0;
  in_flight_j_ = 0.0;
  alpha_ns_per_m_ = 0.0;
  controller_force_n_.setZero();
  play_lag_m_.setZero();
}

PassivityController::InFlight& PassivityController::newest() {
  return in_flight_[static_cast<std::size_t>((oldest_ + slots_ - 1) % slots_)];
}

void PassivityController::push(const Eigen::Vector3d& force_n,
                               const Eigen::Vector3d& velocity_m_per_s, double predicted_j) {
  // The oldest slot has just been observed; the new output takes its place.
  InFlight& slot = in_flight_[static_cast<std::size_t>(oldest_)];
  slot.force_n = force_n;
  slot.velocity_m_per_s = velocity_m_per_s;
  slot.predicted_j = predicted_j;
  oldest_ = (oldest_ + 1) % slots_;
  sumInFlight();
}

void PassivityController::sumInFlight() {
  // Summed afresh (at most four terms) rather than updated by += and -=, so that rounding cannot
  // drift over hours of ticks.
  in_flight_j_ = 0.0;
  for (int i = 0; i < slots_; ++i) {
    in_flight_j_ += in_flight_[static_cast<std::size_t>(i)].predicted_j;
  }
}

Eigen::Vector3d PassivityController::played(const Eigen::Vector3d& velocity_reading_m_per_s, bool commit) {
  // The play operator (header): the observed position moves only where the reading has left the
  // band of one count around it, and then by what lies beyond the band.
  const double w = config_.quantisation_play_m;
  if (!(w > 0.0)) return velocity_reading_m_per_s;
  const double t = config_.period_s;
  Eigen::Vector3d v = Eigen::Vector3d::Zero();
  Eigen::Vector3d lag = play_lag_m_;
  for (int k = 0; k < 3; ++k) {
    const double e = lag[k] + velocity_reading_m_per_s[k] * t;
    const double held = std::clamp(e, -w, w);
    v[k] = (e - held) / t;
    lag[k] = held;
  }
  if (commit && v.allFinite() && lag.allFinite()) play_lag_m_ = lag;
  return v;
}

void PassivityController::observeHeldPeriods(const Eigen::Vector3d& pen_velocity_m_per_s, double held_periods) {
  if (!(held_periods > 0.0)) return;
  const InFlight& due = in_flight_[static_cast<std::size_t>(oldest_)];
  const double held_j = -due.force_n.dot(played(pen_velocity_m_per_s, false)) * config_.period_s * held_periods;
  if (std::isfinite(held_j)) observed_j_ += held_j;  // apply() caps the reservoir next
}

Eigen::Vector3d PassivityController::apply(const Eigen::Vector3d& force_on_pen_n,
                                           const Eigen::Vector3d& velocity_reading_m_per_s) {
  const double t = config_.period_s;
  const Eigen::Vector3d pen_velocity_m_per_s = played(velocity_reading_m_per_s, true);
  const InFlight& due = in_flight_[static_cast<std::size_t>(oldest_)];
  const double still_in_flight_j = in_flight_j_ - due.predicted_j;
  alpha_ns_per_m_ = 0.0;
  controller_force_n_.setZero();

  const double observed_step_j = -due.force_n.dot(pen_velocity_m_per_s) * t;
  const double predicted_ve_j = -force_on_pen_n.dot(pen_velocity_m_per_s) * t;
  if (!std::isfinite(observed_step_j) || !std::isfinite(predicted_ve_j)) {
    // A lost observation: better unobserved than a NaN or infinity stuck in E for ever.
    push(force_on_pen_n.allFinite() ? force_on_pen_n : Eigen::Vector3d::Zero(),
         Eigen::Vector3d::Zero(), 0.0);
    return force_on_pen_n;
  }

  observed_j_ += observed_step_j;
  double cap_j = config_.max_reservoir_j;
  if (config_.stored_energy_stiffness_n_per_m > 0.0) {
    cap_j += force_on_pen_n.squaredNorm() / (2.0 * config_.stored_energy_stiffness_n_per_m);
  }
  observed_j_ = std::min(observed_j_, cap_j);

  // Motion the play still holds back (under a count per axis) that went into the force: the
  // reading says the environment has absorbed it; counting it keeps the first count of a motion on
  // one axis from reading as generation while another axis's motion already passes. Never
  // negative, so a toggle or a motion out of the force adds nothing.
  // (Finite: the force was checked above and the play only keeps finite lags.)
  const double held_back_j = std::max(0.0, -force_on_pen_n.dot(play_lag_m_));
  const double predicted_j = observed_j_ + still_in_flight_j + predicted_ve_j + held_back_j;
  double credit_j = 0.0;
  if (enabled_ && predicted_j < 0.0) {
    const double v2 = pen_velocity_m_per_s.squaredNorm();
    const double v = std::sqrt(v2);
    // alpha = min(-W / (T v^2), alpha_max, F_max / v), written without dividing by v.
    double alpha = config_.max_damping_ns_per_m;
    if (-predicted_j < alpha * t * v2) alpha = -predicted_j / (t * v2);
    if (alpha * v > config_.max_force_n) alpha = config_.max_force_n / v;
    alpha_ns_per_m_ = alpha;
    controller_force_n_ = -alpha * pen_velocity_m_per_s;
    credit_j = alpha * v2 * t;
    if (credit_j > 0.0) {
      ++active_ticks_;
      dissipated_j_ += credit_j;
    }
  }
  const Eigen::Vector3d out_n = force_on_pen_n + controller_force_n_;
  push(out_n, pen_velocity_m_per_s, predicted_ve_j + credit_j);
  return out_n;
}

void PassivityController::recordAppliedForce(const Eigen::Vector3d& applied_force_n) {
  InFlight& slot = newest();
  const Eigen::Vector3d applied =
      applied_force_n.allFinite() ? applied_force_n : Eigen::Vector3d::Zero();
  const double predicted_j = -applied.dot(slot.velocity_m_per_s) * config_.period_s;
  if (!std::isfinite(predicted_j)) return;
  slot.force_n = applied;
  slot.predicted_j = predicted_j;
  sumInFlight();
}

double quantisationPlay(const dev::DeviceSpec& spec) {
  if (!std::isfinite(spec.position_resolution_m) || !(spec.position_resolution_m > 0.0)) return 0.0;
  // One count, plus a hair so a one-count toggle stays inside the play despite rounding.
  return 1.001 * spec.position_resolution_m;
}

PassivityConfig servoPassivityConfig(const dev::DeviceSpec& spec, double period_s,
                                     double rendered_stiffness_n_per_m, bool enabled) {
  PassivityConfig c = PassivityConfig::fromSpec(spec, period_s, rendered_stiffness_n_per_m);
  c.enabled = enabled;
  c.quantisation_play_m = quantisationPlay(spec);
  return c;
}

}  // namespace thx::srv
