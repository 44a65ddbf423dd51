#include "server/missed_tick_policy.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "base/error.hpp"
#include "base/number_text.hpp"

namespace thx::srv {
namespace {

[[noreturn]] void reject(const char* field, double value, const std::string& expected) {
  throw thx::Error(thx::Error::Kind::Config,
                   std::string("missed-tick policy: ") + field + " = " + numberText(value) + ": expected " + expected);
}

}  // namespace

MissedTickPolicyConfig MissedTickPolicyConfig::fromSpec(const dev::DeviceSpec& spec,
                                                        double rendered_stiffness_n_per_m, MissedTickMode mode,
                                                        double period_s) {
  MissedTickPolicyConfig c;
  c.mode = mode;
  if (std::isfinite(period_s) && period_s > 0.0) {
    c.max_stall_ticks = int(std::clamp(std::lround(kMaxStallS / period_s), 1L, 100000L));
    c.window_ticks = int(std::clamp(std::lround(kWindowS / period_s), 1L, long(kMaxMissedWindowTicks)));
  }
  if (std::isfinite(rendered_stiffness_n_per_m) && rendered_stiffness_n_per_m > 0.0 &&
      std::isfinite(spec.continuous_force_n) && spec.continuous_force_n > 0.0) {
    c.max_jump_m = spec.continuous_force_n / rendered_stiffness_n_per_m;
  }
  c.validate();
  return c;
}

void MissedTickPolicyConfig::validate() const {
  if (max_stall_ticks < 0 || max_stall_ticks > 100000) reject("max_stall_ticks", max_stall_ticks, "a tick count in [0, 100000]");
  if (!std::isfinite(max_jump_m) || max_jump_m <= 0.0) reject("max_jump_m", max_jump_m, "a distance > 0 m");
  if (window_ticks < 1 || window_ticks > kMaxMissedWindowTicks) {
    reject("window_ticks", window_ticks, "a tick count in [1, " + std::to_string(kMaxMissedWindowTicks) + "]");
  }
  if (!std::isfinite(min_success_rate) || min_success_rate < 0.0 || min_success_rate > 1.0) {
    reject("min_success_rate", min_success_rate, "a fraction in [0, 1]");
  }
  if (!std::isfinite(hold_decay) || hold_decay < 0.0 || hold_decay > 1.0) reject("hold_decay", hold_decay, "a factor in [0, 1]");
  if (hold_ticks < 0 || hold_ticks > 1000) reject("hold_ticks", hold_ticks, "a tick count in [0, 1000]");
  if (legacy_max_missed_ticks < 1) reject("legacy_max_missed_ticks", legacy_max_missed_ticks, "a tick count >= 1");
}

MissedTickPolicy::MissedTickPolicy(const MissedTickPolicyConfig& config) : config_(config) {
  config_.validate();
  // Whole periods allowed to be missed; the epsilon keeps 0.8 x 100 from flooring to 19.
  max_missed_in_window_ =
      int(std::floor((1.0 - config_.min_success_rate) * double(config_.window_ticks) + 1e-9));
}

void MissedTickPolicy::reset() {
  window_.fill(0);
  cursor_ = 0;
  missed_in_window_ = 0;
  has_last_p_ = false;
  disengaging_ = false;
}

double MissedTickPolicy::successRate() const {
  return 1.0 - double(missed_in_window_) / double(config_.window_ticks);
}

void MissedTickPolicy::pushPeriod(bool missed) {
  std::uint8_t& slot = window_[std::size_t(cursor_)];
  missed_in_window_ += int(missed) - int(slot);
  slot = missed ? 1 : 0;
  cursor_ = (cursor_ + 1) % config_.window_ticks;
}

void MissedTickPolicy::pushPeriods(std::int64_t missed) {
  // A gap longer than the window fills it: only the last window_ticks periods matter.
  const std::int64_t n = missed < config_.window_ticks ? missed : config_.window_ticks;
  for (std::int64_t k = 0; k < n; ++k) pushPeriod(true);
  pushPeriod(false);  // this tick
}

MissedTickDecision MissedTickPolicy::disengage(StallReason reason) {
  MissedTickDecision d;
  d.action = MissedTickAction::Disengage;
  d.reason = reason;
  d.fault = !disengaging_;
  d.held_gain = 0.0;
  ++counters_.disengaged_ticks;
  if (d.fault) {
    if (reason == StallReason::LongStall) ++counters_.long_stalls;
    if (reason == StallReason::Jump) ++counters_.jumps;
    if (reason == StallReason::SuccessRate) ++counters_.success_rate;
  }
  disengaging_ = true;
  return d;
}

MissedTickDecision MissedTickPolicy::observe(std::int64_t missed, const Eigen::Vector3d& p_world, bool valid) {
  if (missed < 0) missed = 0;
  const bool fresh_p = valid && p_world.allFinite();
  const bool jumped = missed > 0 && fresh_p && has_last_p_ && (p_world - last_p_world_).norm() > config_.max_jump_m;
  if (fresh_p) {
    last_p_world_ = p_world;
    has_last_p_ = true;
  }

  if (config_.mode == MissedTickMode::DisengageOnGap) {
    disengaging_ = false;  // the old rule: every long gap is its own fault
    return missed >= config_.legacy_max_missed_ticks ? disengage(StallReason::LongStall) : MissedTickDecision{};
  }

  pushPeriods(missed);
  if (missed > config_.max_stall_ticks) return disengage(StallReason::LongStall);
  if (jumped) return disengage(StallReason::Jump);
  if (missed_in_window_ > max_missed_in_window_) return disengage(StallReason::SuccessRate);
  disengaging_ = false;
  MissedTickDecision d;
  if (missed == 0) return d;
  d.action = MissedTickAction::RideThrough;
  double gain = 1.0;
  d.held_periods = 0.0;
  for (std::int64_t k = 1; k <= missed && k <= config_.hold_ticks; ++k) {
    gain *= config_.hold_decay;
    d.held_periods += gain;
  }
  d.held_gain = missed <= config_.hold_ticks ? gain : 0.0;
  ++counters_.ride_throughs;
  return d;
}

const char* missedTickModeName(MissedTickMode mode) {
  return mode == MissedTickMode::RideThrough ? "ride-through" : "disengage";
}

const char* stallReasonName(StallReason reason) {
  switch (reason) {
    case StallReason::LongStall: return "long-stall";
    case StallReason::Jump: return "jump";
    case StallReason::SuccessRate: return "success-rate";
    case StallReason::None: break;
  }
  return "none";
}

}  // namespace thx::srv
