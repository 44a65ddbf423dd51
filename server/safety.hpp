#pragma once
// SafetyStage: the last stage before the device, always on (docs/design.md §4 rule 3).
//
// Contract (runs inside the 1 kHz servo tick):
//  - apply(), disengage(), requestShutdown() and every accessor are real-time safe: no
//    allocation, lock, logging, exception or system call; constant time; state is plain members.
//  - Only construction (SafetyConfig::validate) may throw (thx::Error, a configuration error).
//  - Whatever apply() receives (NaN, inf, 1e308), its output is finite and |F| <= peak force.
//
// Per tick, in this order:
//  1. Finite check: a non-finite component outputs zero at once and disengages.
//  2. Engage procedure (CHAI3D style): after start or a disengage the output stays zero until the
//     request has been below engage_threshold_n for engage_ticks consecutive ticks; then a gain
//     ramps 0 -> 1 over ramp_in_s and the output is gain x request.
//  3. Peak clamp: |F| <= peak_force_n, direction kept.
//  4. Continuous-force budget: motor heating goes with F^2, so an exponential moving average of
//     |F_out|^2 with thermal_time_constant_s stands in for winding temperature. Once it exceeds
//     continuous_force_n^2, |F| is limited to continuous_force_n (the rated steady state: holding
//     it keeps the average at the rating) until the average falls to
//     continuous_release_fraction x continuous_force_n^2. Below the budget, peaks are allowed.
//     From a cold start, a constant |F| > Fc is first limited after -tau ln(1 - Fc^2/|F|^2)
//     (Desktop, 3 N: 0.85 s; full 7.9 N peak: 0.11 s).
//  5. Force-rate limit: |F_k - F_k-1| <= max_force_rate_n_per_s x period_s (vector step clamp).
//     It applies both ways in normal running; the safety stops (non-finite input, disengage(),
//     the end of a shutdown) step to zero at once, because zero force is always safe.
//  6. Shutdown: requestShutdown() ramps the gain to exactly zero over ramp_out_s (from the current
//     gain if a ramp-in is still running); shutdownComplete() afterwards. Shutdown is final until
//     reset().
//
// The stage assumes one call per period: missed ticks are the servo's business (docs/design.md
// §4 rule 2); they only under-count cooling, which errs on the safe side. A gap the servo rides
// through restarts the rate limit from the force the device held (restartRateLimitFrom()).
#include <Eigen/Core>
#include <cstdint>

#include "device/haptic_device.hpp"

namespace thx::srv {

enum class RampShape {
  Linear,
  Smooth,  // smoothstep 3p^2 - 2p^3: no force-rate step where the ramp starts or ends
};

struct SafetyConfig {
  double period_s = 1e-3;
  double peak_force_n = 0.0;
  double continuous_force_n = 0.0;
  double thermal_time_constant_s = 5.0;
  double continuous_release_fraction = 0.81;  // of Fc^2: RMS back to 0.9 Fc
  double max_force_rate_n_per_s = 5000.0;
  double engage_threshold_n = 0.2;
  int engage_ticks = 3;
  double ramp_in_s = 0.5;
  double ramp_out_s = 0.2;
  RampShape ramp_shape = RampShape::Smooth;

  // Limits from the device, defaults for the rest. max_force_rate_n_per_s =
  // kRateHeadroom x max_stiffness x kFastPenSpeed: the fastest force change a legitimate contact
  // makes is the stiffest wall hit at stroke speed (Desktop: 1000 N/m x 2 m/s = 2000 N/s), so
  // 2.5x that (5000 N/s, 5 N per 1 ms tick) never touches rendering, yet spreads a fault's jump to
  // full peak over two ticks. A spec without a stiffness falls back to 5000 N/s.
  static SafetyConfig fromSpec(const dev::DeviceSpec& spec, double period_s);
  // Throws thx::Error naming the field, its value and what was expected.
  void validate() const;
};

inline constexpr double kRateHeadroom = 2.5;
inline constexpr double kFastPenSpeedMPerS = 2.0;  // scenes cap stroke speed at 2 m/s

// Per-tick status bits; several may be set at once.
enum SafetyFlag : std::uint32_t {
  kSafetyNonFinite = 1u << 0,          // the request had a non-finite component
  kSafetyDisengaged = 1u << 1,         // output forced to zero, waiting for a small request
  kSafetyEngaging = 1u << 2,           // ramp-in running
  kSafetyPeakClamped = 1u << 3,        // |F| cut to the peak force
  kSafetyContinuousLimited = 1u << 4,  // |F| cut to the continuous force
  kSafetyRateLimited = 1u << 5,        // step cut to the rate limit
  kSafetyRampingOut = 1u << 6,         // shutdown ramp running
  kSafetyShutDown = 1u << 7,           // shutdown complete, output zero
  kSafetyBudgetExhausted = 1u << 8,    // this tick the thermal average crossed the budget: the
                                       // continuous limit acts from the next tick (a fault)
};
// The bits meaning "the stage changed a force it was allowed to render" (messages:
// FLAG_SAFETY_CLAMP).
inline constexpr std::uint32_t kSafetyClampMask =
    kSafetyPeakClamped | kSafetyContinuousLimited | kSafetyRateLimited;

struct SafetyCounters {
  std::uint64_t ticks = 0;
  std::uint64_t non_finite = 0;
  std::uint64_t disengaged = 0;
  std::uint64_t engaging = 0;
  std::uint64_t peak_clamped = 0;
  std::uint64_t continuous_limited = 0;
  std::uint64_t rate_limited = 0;
  std::uint64_t ramping_out = 0;
  std::uint64_t disengage_events = 0;  // NaN or disengage() while not already disengaged
};

enum class SafetyState { Disengaged, RampingIn, Engaged, RampingOut, ShutDown };

class SafetyStage {
 public:
  explicit SafetyStage(const SafetyConfig& config);  // validates; may throw

  Eigen::Vector3d apply(const Eigen::Vector3d& requested_force_n);

  // Fault from the servo (missed ticks, invalid reading): zero now, engage procedure again.
  void disengage();
  // The servo rides through a gap (server/missed_tick_policy.hpp): the device was left applying
  // held_gain x the last output, so the next apply()'s rate limit counts from that force rather
  // than from what was written before the gap. held_gain is clamped to [0, 1] (NaN: 0).
  void restartRateLimitFrom(double held_gain);
  void requestShutdown();
  bool shutdownComplete() const { return state_ == SafetyState::ShutDown; }
  // Back to the start-up state (disengaged, cold budget, counters kept).
  void reset();

  SafetyState state() const { return state_; }
  double gain() const { return gain_; }
  std::uint32_t flags() const { return flags_; }  // of the last apply()
  const SafetyCounters& counters() const { return counters_; }
  const Eigen::Vector3d& lastOutput() const { return last_output_n_; }
  double meanSquareForceN2() const { return mean_square_force_n2_; }  // thermal average
  bool continuousLimitActive() const { return continuous_limit_active_; }
  const SafetyConfig& config() const { return config_; }

 private:
  void enterDisengaged();
  double rampGain(std::int64_t tick, std::int64_t ticks) const;
  void stepEngage(double request_norm_n);
  void stepRamps();
  Eigen::Vector3d finish(const Eigen::Vector3d& output_n);

  SafetyConfig config_;
  std::int64_t ramp_in_ticks_ = 0;
  std::int64_t ramp_out_ticks_ = 0;
  double max_step_n_ = 0.0;
  double ema_weight_ = 0.0;  // 1 - exp(-T / tau): exact discretisation of the first-order lag

  SafetyState state_ = SafetyState::Disengaged;
  int small_ticks_ = 0;
  std::int64_t ramp_tick_ = 0;  // ramp-in: ticks done; ramp-out: ticks left
  double gain_ = 0.0;
  double mean_square_force_n2_ = 0.0;
  bool continuous_limit_active_ = false;
  Eigen::Vector3d last_output_n_ = Eigen::Vector3d::Zero();
  std::uint32_t flags_ = 0;
  SafetyCounters counters_;
};

}  // namespace thx::srv
