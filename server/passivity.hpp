#pragma once
// PassivityController: time-domain passivity observer + controller (Hannaford & Ryu 2002), the
// last line of stability defence in the force path (renderer -> passivity -> safety -> device).
//
// Contract (runs inside the 1 kHz servo tick):
//  - apply(), recordAppliedForce() and every accessor are real-time safe: no allocation, lock,
//    logging, exception or system call; constant time; state is plain members.
//  - Only construction (PassivityConfig::validate) may throw (thx::Error, a configuration error).
//  - The controller's force is always -alpha v with 0 <= alpha <= max_damping_ns_per_m and
//    |force| <= max_force_n: it only ever removes energy.
//
// Sign convention. F = force the device applies to the pen (N, world), v = pen velocity (m/s).
// F.v is power delivered to the pen; the virtual environment (VE) absorbs P = -F.v. E is the
// energy the VE has absorbed since reset(): pushing into a spring wall (F along +n, v along -n)
// raises E by 1/2 K x^2, releasing gives it back. A passive VE keeps E >= 0; E < 0 means the
// sampled loop has created energy.
//
// Observer, aligned with the zero-order hold. The force written at tick j acts over the interval
// after the device applies it. With a backward-difference velocity v_k = (x_k - x_k-1) / T the
// exact energy of the interval that ended at tick k is -F_applied . v_k T, where F_applied is the
// output written at tick k - 1 - output_delay_ticks. Pairing v_k with the force computed at tick k
// instead (the textbook form) sees a sampled spring as slightly *dissipative* (+1/2 K dx^2 per
// tick) when in truth the hold makes it generate that much, so it would never catch the
// instability it is there for. output_delay_ticks = 0 is hapticd's device contract (read ->
// compute -> write in one tick); 1 suits drivers that apply a write one tick later (CHAI3D's
// PHANToM wrapper). When unsure, err high: understating the delay lets a sampled-wall
// oscillation through (tests/server/test_passivity.cpp), overstating it only adds damping of
// about K T per extra tick while the controller acts. A filtered velocity estimate lags too and
// counts as delay.
//
// Controller. Each tick predicts the energy after the new force has acted with the current
// velocity: W = E_observed + (predicted energy of outputs still in flight) - F_ve.v T. If W < 0 it
// adds a damper alpha = -W / (T |v|^2), bounded by max_damping_ns_per_m and by max_force_n / |v|
// (so v = 0 needs no guard: the bound wins and the force is zero), and credits alpha |v|^2 T to
// the prediction. Predictions are replaced by observations once the interval has happened, so the
// credit is counted once and errors do not accumulate. One scalar alpha for the 3-D port (total
// energy, as the design asks) rather than one observer per axis.
//
// Reservoir cap. Dissipation (the VE's own damping, the hand) piles up positive E without bound,
// and a large reservoir lets an oscillation run for a long time before the controller acts. E is
// therefore capped at max_reservoir_j + |F_ve|^2 / (2 K), K = stored_energy_stiffness_n_per_m: the
// second term is the energy a spring of stiffness K holds while pushing with F_ve, which the VE is
// entitled to return, so releasing a press is not damped; the first is the free slack. Default
// slack 1 mJ: the energy of a 1.4 mm / 1.4 N oscillation on a 1000 N/m wall, or 0.2 m/s of the
// simulator's 45 g tip mass, the most a sampling oscillation may build before the controller
// answers. K = 0 (unknown) makes the cap absolute, and then any press storing more than the slack
// is partly damped on release.
//
// Quantisation play. A pen at rest on an encoder count boundary toggles its reading by one
// count; the finite-difference velocity toggles by +-q/T and the observer books K q^2 / 2 of
// "generated" energy per toggle (real for the quantised path, 0.3 um of true motion). Unchecked,
// the controller sat at its bound and turned the toggling into a 0.3 N, 250 Hz ripple on a pen
// at rest (docs/stability.md, bug B). The observer therefore reads the pen through a play
// (backlash) operator of one count per axis: the observed position stays put while the reading
// is within a count of it, and is dragged along a count behind once the reading moves further.
// A toggle moves nothing; a motion in one direction passes whole after its first count, however
// slowly it goes and on every axis, so a pen sliding down a slope feeds the spring as it should
// (bug D), and the same motion reads the same at any servo rate. Until issue 30 the band was one
// count per *period* on the velocity: at 2 and 4 kHz it hid every motion slower than 2 or 4
// counts per millisecond, and the controller acted on the default scene for 79 and 315 ticks of a
// lock-step run (0 with the play). The controller's prediction also counts the motion the play
// holds back where it went into the force (at most a count per axis times the force; never
// negative), so that the first count of a motion on one axis, held back while another axis's
// already passes, does not read as generation. The play hides up to a count of travel at each
// reversal, so it is opt-in: hapticd sets it from the device's resolution (quantisationPlay),
// fromSpec() leaves it off.
//
// No reset on contact loss. A full reset would forgive energy the loop has just created: a pen
// bouncing on a wall gains energy at each contact, and resetting at each lift-off would let the
// bounce grow for ever. Forgetting only positive slack at lift-off is sound for a memoryless
// spring but wrong for a VE that stores energy elsewhere (a dynamic proxy, physics objects); the
// cap already bounds the slack, so E is left alone. reset() is for (re-)engagement.
#include <Eigen/Core>
#include <array>
#include <cstdint>

#include "device/haptic_device.hpp"

namespace thx::srv {

inline constexpr int kMaxOutputDelayTicks = 3;

struct PassivityConfig {
  double period_s = 1e-3;
  double max_damping_ns_per_m = 0.0;  // alpha bound
  double max_force_n = 0.0;           // |controller force| bound
  double max_reservoir_j = 1e-3;      // slack above the stored spring energy
  double stored_energy_stiffness_n_per_m = 0.0;  // rendered K; 0: the VE stores nothing
  int output_delay_ticks = 0;         // 0..kMaxOutputDelayTicks
  double quantisation_play_m = 0.0;  // per axis, the play operator's width; 0 = off; quantisationPlay() for hapticd
  bool enabled = true;

  // max_damping_ns_per_m = the device's max damping (its recommended limit for stable damping);
  // max_force_n = the device's continuous force: enough to soak a buzz, small enough that the
  // controller cannot itself shove the pen. K = the stiffness the renderer uses.
  static PassivityConfig fromSpec(const dev::DeviceSpec& spec, double period_s,
                                  double rendered_stiffness_n_per_m);
  void validate() const;  // throws thx::Error naming field, value and expectation
};

// One encoder count of this device (and a hair), for PassivityConfig::quantisation_play_m.
double quantisationPlay(const dev::DeviceSpec& spec);

// The configuration hapticd runs (and the tools that reproduce it): fromSpec() plus the
// quantisation play, with the controller on or off.
PassivityConfig servoPassivityConfig(const dev::DeviceSpec& spec, double period_s,
                                     double rendered_stiffness_n_per_m, bool enabled);

class PassivityController {
 public:
  explicit PassivityController(const PassivityConfig& config);  // validates; may throw

  // force_on_pen_n: the VE's force; pen_velocity_m_per_s: this tick's velocity estimate
  // (ideally the backward difference of sampled positions). Returns force + controller force.
  // Non-finite inputs pass through untouched (the safety stage handles them) and are not observed.
  Eigen::Vector3d apply(const Eigen::Vector3d& force_on_pen_n,
                        const Eigen::Vector3d& pen_velocity_m_per_s);
  // A gap the servo rides through (server/missed_tick_policy.hpp), before this tick's apply():
  // the device went on applying the last output x its watchdog's hold over the skipped periods,
  // held_periods = the sum of those gains. Books -F . v T held_periods with this tick's velocity
  // (the reading's average over the gap), the work apply() alone would miss.
  void observeHeldPeriods(const Eigen::Vector3d& pen_velocity_m_per_s, double held_periods);
  // Optional, after the safety stage: the force actually written this tick, so the observer
  // accounts for clamps, ramps and disengagement. Without it apply()'s output is assumed.
  void recordAppliedForce(const Eigen::Vector3d& applied_force_n);

  void setEnabled(bool enabled) { enabled_ = enabled; }  // the observer always runs
  // A scene switch renders another stiffness: the reservoir cap's K from then on. Real-time safe;
  // the caller has checked it (finite, >= 0; PassivityConfig::validate) off the servo thread.
  void setStoredEnergyStiffness(double k_n_per_m) { config_.stored_energy_stiffness_n_per_m = k_n_per_m; }
  bool enabled() const { return enabled_; }
  void reset();

  double energy() const { return observed_j_ + in_flight_j_; }  // J, incl. predictions
  double observedEnergy() const { return observed_j_; }         // J, measured intervals only
  double alpha() const { return alpha_ns_per_m_; }               // N s/m, this tick
  const Eigen::Vector3d& controllerForce() const { return controller_force_n_; }
  std::uint64_t activeTicks() const { return active_ticks_; }
  double dissipatedEnergy() const { return dissipated_j_; }  // J credited by the controller
  const PassivityConfig& config() const { return config_; }

 private:
  struct InFlight {
    Eigen::Vector3d force_n = Eigen::Vector3d::Zero();
    Eigen::Vector3d velocity_m_per_s = Eigen::Vector3d::Zero();
    double predicted_j = 0.0;
  };
  InFlight& newest();
  // The velocity the observer reads: the reading's displacement this period through the play
  // operator (header); `commit` moves the operator (apply), else it is only looked at.
  Eigen::Vector3d played(const Eigen::Vector3d& velocity_reading_m_per_s, bool commit);
  void push(const Eigen::Vector3d& force_n, const Eigen::Vector3d& velocity_m_per_s,
            double predicted_j);
  void sumInFlight();

  PassivityConfig config_;
  bool enabled_ = true;
  std::array<InFlight, kMaxOutputDelayTicks + 1> in_flight_{};
  int slots_ = 1;
  int oldest_ = 0;  // the output due for observation this tick
  double observed_j_ = 0.0;
  double in_flight_j_ = 0.0;
  double alpha_ns_per_m_ = 0.0;
  Eigen::Vector3d controller_force_n_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d play_lag_m_ = Eigen::Vector3d::Zero();  // reading - observed position, per axis in [-w, w]
  std::uint64_t active_ticks_ = 0;
  double dissipated_j_ = 0.0;
};

}  // namespace thx::srv
