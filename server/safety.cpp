#include "server/safety.hpp"

#include "base/number_text.hpp"
#include "base/error.hpp"

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace thx::srv {
namespace {

[[noreturn]] void reject(const char* field, double value, const std::string& expected) {
  throw thx::Error(thx::Error::Kind::Config, std::string("safety config: ") + field + " = " + numberText(value) +
                              ": expected " + expected);
}

void requirePositive(const char* field, double value, const char* unit) {
  if (!std::isfinite(value) || value <= 0.0) {
    reject(field, value, std::string("a finite number > 0 ") + unit);
  }
}

void requireRampTime(const char* field, double value) {
  // The upper bound keeps the tick count far from integer overflow; nobody ramps for an hour.
  if (!std::isfinite(value) || value < 0.0 || value > 3600.0) {
    reject(field, value, "a time in [0, 3600] s");
  }
}

std::int64_t ticksFor(double duration_s, double period_s) {
  // Rounded, not ceiled: 0.2 / 0.001 is 200.00000000000003 in floating point.
  return static_cast<std::int64_t>(std::llround(duration_s / period_s));
}

// |f| without overflow: 1e308 components must not turn into an infinite norm that would wipe out
// the direction when the force is scaled back.
struct Magnitude {
  Eigen::Vector3d unit_scaled;  // f / max|f_i|: finite, largest component +-1
  double max_abs = 0.0;
  double scaled_norm = 0.0;  // |unit_scaled| in [1, sqrt 3]
};

Magnitude magnitude(const Eigen::Vector3d& f) {
  Magnitude m;
  m.max_abs = f.cwiseAbs().maxCoeff();
  if (m.max_abs > 0.0) {
    m.unit_scaled = f / m.max_abs;
    m.scaled_norm = m.unit_scaled.norm();
  } else {
    m.unit_scaled.setZero();
  }
  return m;
}

// Scales f down to |f| = limit if it is longer; returns whether it did.
bool clampNorm(Eigen::Vector3d& f, double limit) {
  const Magnitude m = magnitude(f);
  if (m.max_abs == 0.0 || m.max_abs <= limit / m.scaled_norm) return false;
  f = m.unit_scaled * (limit / m.scaled_norm);
  return true;
}

}  // namespace

SafetyConfig SafetyConfig::fromSpec(const dev::DeviceSpec& spec, double period_s) {
  SafetyConfig c;
  c.period_s = period_s;
  c.peak_force_n = spec.peak_force_n;
  c.continuous_force_n = spec.continuous_force_n;
  if (std::isfinite(spec.max_stiffness_n_per_m) && spec.max_stiffness_n_per_m > 0.0) {
    c.max_force_rate_n_per_s = kRateHeadroom * spec.max_stiffness_n_per_m * kFastPenSpeedMPerS;
  }
  try {
    c.validate();
  } catch (const thx::Error& e) {
    throw thx::Error(thx::Error::Kind::Config, "device model '" + spec.model + "': " + e.what());
  }
  return c;
}

void SafetyConfig::validate() const {
  if (!std::isfinite(period_s) || period_s < 1e-6 || period_s > 1.0) {
    reject("period_s", period_s, "a servo period in [1e-6, 1] s");
  }
  requirePositive("peak_force_n", peak_force_n, "N");
  if (!std::isfinite(continuous_force_n) || continuous_force_n <= 0.0 ||
      continuous_force_n > peak_force_n) {
    reject("continuous_force_n", continuous_force_n,
           "a number in (0, peak_force_n = " + numberText(peak_force_n) + "] N");
  }
  requirePositive("thermal_time_constant_s", thermal_time_constant_s, "s");
  if (!std::isfinite(continuous_release_fraction) || continuous_release_fraction <= 0.0 ||
      continuous_release_fraction > 1.0) {
    reject("continuous_release_fraction", continuous_release_fraction,
           "a fraction of continuous_force_n^2 in (0, 1]");
  }
  requirePositive("max_force_rate_n_per_s", max_force_rate_n_per_s, "N/s");
  if (!std::isfinite(engage_threshold_n) || engage_threshold_n <= 0.0 ||
      engage_threshold_n > peak_force_n) {
    reject("engage_threshold_n", engage_threshold_n,
           "a force in (0, peak_force_n = " + numberText(peak_force_n) + "] N");
  }
  if (engage_ticks < 1 || engage_ticks > 100000) {
    reject("engage_ticks", engage_ticks, "a tick count in [1, 100000]");
  }
  requireRampTime("ramp_in_s", ramp_in_s);
  requireRampTime("ramp_out_s", ramp_out_s);
}

SafetyStage::SafetyStage(const SafetyConfig& config) : config_(config) {
  config_.validate();
  ramp_in_ticks_ = ticksFor(config_.ramp_in_s, config_.period_s);
  ramp_out_ticks_ = ticksFor(config_.ramp_out_s, config_.period_s);
  max_step_n_ = config_.max_force_rate_n_per_s * config_.period_s;
  ema_weight_ = -std::expm1(-config_.period_s / config_.thermal_time_constant_s);
}

void SafetyStage::enterDisengaged() {
  state_ = SafetyState::Disengaged;
  small_ticks_ = 0;
  ramp_tick_ = 0;
  gain_ = 0.0;
  last_output_n_.setZero();  // the next output is zero anyway; the rate limit starts from there
}

void SafetyStage::disengage() {
  if (state_ == SafetyState::RampingOut || state_ == SafetyState::ShutDown) {
    // Already on the way out: a fault just finishes the shutdown.
    state_ = SafetyState::ShutDown;
    gain_ = 0.0;
    last_output_n_.setZero();
    return;
  }
  if (state_ != SafetyState::Disengaged) ++counters_.disengage_events;
  enterDisengaged();
}

void SafetyStage::restartRateLimitFrom(double held_gain) {
  const double g = held_gain > 0.0 ? (held_gain < 1.0 ? held_gain : 1.0) : 0.0;  // NaN fails both tests: 0
  last_output_n_ *= g;
}

void SafetyStage::requestShutdown() {
  switch (state_) {
    case SafetyState::Engaged:
      ramp_tick_ = ramp_out_ticks_;
      break;
    case SafetyState::RampingIn:
      // Continue from (at most) the current gain so the force never rises on the way out.
      ramp_tick_ = ramp_in_ticks_ > 0
                       ? static_cast<std::int64_t>(std::floor(static_cast<double>(ramp_tick_) *
                                                              static_cast<double>(ramp_out_ticks_) /
                                                              static_cast<double>(ramp_in_ticks_)))
                       : 0;
      break;
    case SafetyState::Disengaged:
      ramp_tick_ = 0;
      break;
    case SafetyState::RampingOut:
    case SafetyState::ShutDown:
      return;
  }
  if (ramp_tick_ <= 0) {
    state_ = SafetyState::ShutDown;
    gain_ = 0.0;
  } else {
    state_ = SafetyState::RampingOut;
  }
}

void SafetyStage::reset() {
  enterDisengaged();
  mean_square_force_n2_ = 0.0;
  continuous_limit_active_ = false;
  flags_ = 0;
}

double SafetyStage::rampGain(std::int64_t tick, std::int64_t ticks) const {
  const double p = static_cast<double>(tick) / static_cast<double>(ticks);
  return config_.ramp_shape == RampShape::Linear ? p : p * p * (3.0 - 2.0 * p);
}

void SafetyStage::stepEngage(double request_norm_n) {
  small_ticks_ = request_norm_n < config_.engage_threshold_n ? small_ticks_ + 1 : 0;
  if (small_ticks_ < config_.engage_ticks) return;
  ramp_tick_ = 0;
  gain_ = 0.0;
  state_ = SafetyState::RampingIn;
  if (ramp_in_ticks_ == 0) {
    state_ = SafetyState::Engaged;
    gain_ = 1.0;
  }
}

void SafetyStage::stepRamps() {
  if (state_ == SafetyState::RampingIn) {
    ++ramp_tick_;
    if (ramp_tick_ >= ramp_in_ticks_) {
      state_ = SafetyState::Engaged;
      gain_ = 1.0;
    } else {
      gain_ = rampGain(ramp_tick_, ramp_in_ticks_);
      flags_ |= kSafetyEngaging;
    }
  } else if (state_ == SafetyState::RampingOut) {
    --ramp_tick_;
    flags_ |= kSafetyRampingOut;
    if (ramp_tick_ <= 0) {
      state_ = SafetyState::ShutDown;
      gain_ = 0.0;
    } else {
      gain_ = rampGain(ramp_tick_, ramp_out_ticks_);
    }
  }
}

Eigen::Vector3d SafetyStage::apply(const Eigen::Vector3d& requested_force_n) {
  flags_ = 0;
  const Eigen::Vector3d zero = Eigen::Vector3d::Zero();

  if (!requested_force_n.allFinite()) {
    flags_ |= kSafetyNonFinite;
    if (state_ == SafetyState::RampingOut || state_ == SafetyState::ShutDown) {
      disengage();
      flags_ |= kSafetyShutDown;
    } else {
      disengage();
      flags_ |= kSafetyDisengaged;
    }
    return finish(zero);
  }
  if (state_ == SafetyState::ShutDown) {
    flags_ |= kSafetyShutDown;
    return finish(zero);
  }
  if (state_ == SafetyState::Disengaged) {
    flags_ |= kSafetyDisengaged;
    const Magnitude m = magnitude(requested_force_n);
    stepEngage(m.max_abs * m.scaled_norm);
    return finish(zero);
  }

  stepRamps();
  if (state_ == SafetyState::ShutDown) {
    flags_ |= kSafetyShutDown;
    return finish(zero);  // exactly zero at the end of the ramp, whatever the rate limit says
  }

  Eigen::Vector3d f = gain_ * requested_force_n;
  if (clampNorm(f, config_.peak_force_n)) flags_ |= kSafetyPeakClamped;
  if (continuous_limit_active_ && clampNorm(f, config_.continuous_force_n)) {
    flags_ |= kSafetyContinuousLimited;
  }
  const Eigen::Vector3d step = f - last_output_n_;
  const double step_n = step.norm();  // finite: both ends are within the peak force
  if (step_n > max_step_n_) {
    f = last_output_n_ + step * (max_step_n_ / step_n);
    flags_ |= kSafetyRateLimited;
  }
  // f lies between two points inside the peak ball; this only absorbs rounding so that the
  // bound cannot creep over many ticks.
  clampNorm(f, config_.peak_force_n);
  return finish(f);
}

Eigen::Vector3d SafetyStage::finish(const Eigen::Vector3d& output_n) {
  const double continuous_n2 = config_.continuous_force_n * config_.continuous_force_n;
  mean_square_force_n2_ += ema_weight_ * (output_n.squaredNorm() - mean_square_force_n2_);
  if (!continuous_limit_active_ && mean_square_force_n2_ > continuous_n2) {
    continuous_limit_active_ = true;
    flags_ |= kSafetyBudgetExhausted;
  } else if (continuous_limit_active_ &&
             mean_square_force_n2_ <= config_.continuous_release_fraction * continuous_n2) {
    continuous_limit_active_ = false;
  }
  last_output_n_ = output_n;

  ++counters_.ticks;
  if (flags_ & kSafetyNonFinite) ++counters_.non_finite;
  if (flags_ & kSafetyDisengaged) ++counters_.disengaged;
  if (flags_ & kSafetyEngaging) ++counters_.engaging;
  if (flags_ & kSafetyPeakClamped) ++counters_.peak_clamped;
  if (flags_ & kSafetyContinuousLimited) ++counters_.continuous_limited;
  if (flags_ & kSafetyRateLimited) ++counters_.rate_limited;
  if (flags_ & kSafetyRampingOut) ++counters_.ramping_out;
  return output_n;
}

}  // namespace thx::srv
