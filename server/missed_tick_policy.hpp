#pragma once
// MissedTickPolicy: what the servo does about device periods it did not serve (docs/design.md §4
// rule 2). Kept out of the tick so it can be unit-tested on tick sequences with no clock at all,
// as ros2_control keeps its timing policy apart. THIS IS REAL-TIME CODE (called from servo.cpp).
//
// Contract:
//  - observe() and every accessor are real-time safe: no allocation, lock, logging, exception or
//    system call; plain members; O(1) per tick, O(min(missed, window_ticks)) after a gap.
//  - Only construction (MissedTickPolicyConfig::validate) may throw (thx::Error, configuration).
//  - Decisions depend only on the sequence of observe() calls (periods skipped, position,
//    validity): the policy reads no clock, so lock-step and real time decide alike.
//
// What a gap means for the pen (the device contract, device/haptic_device.hpp): while the servo
// is away the device holds its last force x hold_decay per period for hold_ticks periods, then
// outputs zero. The servo always returns on the grid (the pacer realigns, no catch-up burst).
//
// RideThrough mode (hapticd's default). For a serviced tick after `missed` skipped periods:
//  1. missed > max_stall_ticks                       -> Disengage, reason LongStall;
//  2. missed > 0 and the pen moved more than max_jump_m since the last valid reading
//     (an invalid reading is neither checked nor kept: the servo resets the renderer for it)
//                                                     -> Disengage, reason Jump;
//  3. more than max_missed_in_window of the last window_ticks device periods skipped (the success
//     rate, serviced / all, below min_success_rate, as libfranka counts it)
//                                                     -> Disengage, reason SuccessRate;
//  4. missed > 0                                      -> RideThrough, held_gain = the fraction of
//     the last force the device was still applying when the servo came back (hold_decay^missed
//     for missed <= hold_ticks, else 0): the servo restarts the safety stage's force-rate limit
//     from that force, so the force comes back no faster than the rate limit allows any tick;
//  5. otherwise                                       -> Run.
//  A Disengage is repeated on every tick its condition holds (a success rate stays low until the
//  gaps leave the window); `fault` is set only on the first of a run of Disengage decisions, so
//  one overload is one fault (one flight record). The window counts every device period, gaps
//  and serviced ticks alike; it starts full of serviced periods.
//
// DisengageOnGap mode (the policy before issue 12; hapticd --missed-policy disengage, kept for
// comparison): missed >= legacy_max_missed_ticks -> Disengage (fault every time), anything
// shorter -> Run, the force simply resumes.
//
// Why riding through is safe, with the bounds: docs/hapticd.md "Missed ticks and faults".
#include <Eigen/Core>
#include <array>
#include <cstdint>

#include "device/haptic_device.hpp"

namespace thx::srv {

enum class MissedTickMode { RideThrough, DisengageOnGap };

inline constexpr int kMaxMissedWindowTicks = 4096;

struct MissedTickPolicyConfig {
  MissedTickMode mode = MissedTickMode::RideThrough;
  int max_stall_ticks = 20;  // the longest gap ridden through (libfranka stops after 20 lost)
  // Pen travel over a gap beyond which the proxy's history is not trusted. fromSpec(): the
  // distance at which the rendered stiffness reaches the device's continuous force.
  double max_jump_m = 0.002;
  int window_ticks = 100;          // success-rate window, device periods (100 ms at 1 kHz)
  double min_success_rate = 0.8;   // serviced / all over the window
  double hold_decay = 0.5;         // the device's watchdog (device/haptic_device.hpp)
  int hold_ticks = 2;
  int legacy_max_missed_ticks = 3;  // DisengageOnGap

  // hapticd's: max_jump_m = continuous force / rendered stiffness (Desktop at 600 N/m: 2.0 mm);
  // the longest gap and the success-rate window in time, kMaxStallS and kWindowS at any servo
  // period (20 and 100 ticks at 1 kHz, 80 and 400 at 4 kHz), so a scheduler hiccup of a given
  // length is decided alike at every rate (issue 30: counted in ticks, two 3 ms stalls 10 ms
  // apart were a success-rate fault at 4 kHz and nothing at 1 kHz).
  static constexpr double kMaxStallS = 0.020;
  static constexpr double kWindowS = 0.100;
  static MissedTickPolicyConfig fromSpec(const dev::DeviceSpec& spec, double rendered_stiffness_n_per_m,
                                         MissedTickMode mode, double period_s = 1e-3);
  void validate() const;  // throws thx::Error naming the field, its value and what was expected
};

enum class MissedTickAction { Run, RideThrough, Disengage };
enum class StallReason { None, LongStall, Jump, SuccessRate };

struct MissedTickDecision {
  MissedTickAction action = MissedTickAction::Run;
  StallReason reason = StallReason::None;  // Disengage only
  bool fault = false;                      // the first Disengage of a run
  double held_gain = 1.0;                  // RideThrough: device force left / last force written
  double held_periods = 0.0;  // RideThrough: sum of the device's hold gains over the gap (force x periods)
};

struct MissedTickCounters {
  std::uint64_t ride_throughs = 0;  // gaps ridden through
  std::uint64_t long_stalls = 0;    // faults by reason
  std::uint64_t jumps = 0;
  std::uint64_t success_rate = 0;
  std::uint64_t disengaged_ticks = 0;  // ticks decided Disengage
};

class MissedTickPolicy {
 public:
  explicit MissedTickPolicy(const MissedTickPolicyConfig& config);  // validates; may throw

  // One serviced tick: `missed` device periods were skipped just before it (TickTiming::missed).
  MissedTickDecision observe(std::int64_t missed, const Eigen::Vector3d& p_world, bool valid);
  // Back to the state after construction (counters kept).
  void reset();

  double successRate() const;  // over the window, as of the last observe()
  int missedInWindow() const { return missed_in_window_; }
  const MissedTickCounters& counters() const { return counters_; }
  const MissedTickPolicyConfig& config() const { return config_; }

 private:
  void pushPeriod(bool missed);
  void pushPeriods(std::int64_t missed);
  MissedTickDecision disengage(StallReason reason);

  MissedTickPolicyConfig config_;
  int max_missed_in_window_ = 0;
  std::array<std::uint8_t, kMaxMissedWindowTicks> window_{};  // 1: a skipped period
  int cursor_ = 0;
  int missed_in_window_ = 0;
  Eigen::Vector3d last_p_world_ = Eigen::Vector3d::Zero();
  bool has_last_p_ = false;
  bool disengaging_ = false;  // the last decision was Disengage
  MissedTickCounters counters_;
};

const char* missedTickModeName(MissedTickMode mode);  // "ride-through", "disengage"
const char* stallReasonName(StallReason reason);      // "long-stall", "jump", "success-rate", "none"

}  // namespace thx::srv
