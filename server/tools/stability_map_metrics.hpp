#pragma once
// What one map cell measured over its final window, and the verdict drawn from it.
//
// Everything is measured on the simulator's TRUE state (SimTruth: the unquantised pen position,
// the motor force actually applied and the motor's work), plus the force the servo commanded (the
// safety stage's output, TickRecord::f_out). Axes are plane-local: lateral = x, across the valley;
// normal = z, along the plane's normal. (The map's surface has the identity pose, so local = world.)
//
// Amplitudes are peak-to-peak after removing the least-squares linear trend over the window, and
// an axis whose residual crosses its mean fewer than min_crossings times (with a one-count dead
// band) while the motors do less than drift_energy_j of net work is drifting, not oscillating: a pen still
// sinking after a hard push (the safety stage's continuous-force limit lets it through) is not a
// limit cycle. Excursion (below) catches a pen
// that drifts out of its valley.
//
// Energy over the window [t0, t1] (hand target fixed during the hold):
//   motor_work_j      = sum of SimTruth::motor_work_j (integral of F_motor . dx, per 0.1 ms step)
//   energy_injected_j = motor_work_j - dKE - dU_hand
// with KE = (m_pen + m_hand) |v|^2 / 2 and U_hand the potential of the hand's spring and constant
// push, U_hand(x) = -F0 . d - d' A d / 2, d = x - x_target, F0 and A the hand force and its
// stiffness matrix at the target (read from SimDynamics, so the hand model's anisotropy is
// honoured). The rest of the body's energy balance is the hand's damping, the mechanism's damping
// and friction, all dissipative, so energy_injected_j is exactly the energy those burnt in the
// window: ~0 for a pen at rest, > 0 for a sustained oscillation. In a periodic steady state it
// equals motor_work_j, the net energy the rendering loop fed in; while the pen sinks, the hand's
// push feeds part of it (motor_work_j is then negative: the motors resist). (It is computed, not
// summed, so the integrator's energy error enters; small with the symplectic integrator at 10 kHz.)
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace thx::srv::stab {

// CannotHold: the device could not hold the push. The safety stage's continuous-force (thermal)
// budget held the force below what the hand pushes with and the pen sank through the floor, so
// the cell says nothing about the valley (issue 12); the map's claims count only the other three.
enum class Verdict { Stable = 0, LimitCycle = 1, Unstable = 2, CannotHold = 3 };
constexpr int kVerdicts = 4;
const char* verdictName(Verdict v);  // "stable", "limit-cycle", "unstable", "cannot-hold"
// Unstable > limit-cycle > stable > cannot-hold: which verdict a square of several forces shows.
int severity(Verdict v);

// The verdict's thresholds; docs/stability.md justifies the numbers.
struct Thresholds {
  double encoder_resolution_m = 2.3e-5;
  // stable: both amplitudes within 2 encoder counts (the floor a sampled, quantised loop settles
  // to: +-1 count of chatter), and the commanded force ripple below the buzz threshold.
  double stable_amplitude_counts = 2.0;
  double buzz_force_pp_n = 0.1;
  // unstable: the pen leaves its valley floor by more than this fraction of the period (it is
  // thrown up the walls, not buzzing at the crease) ...
  double excursion_period_fraction = 0.25;
  // ... or the output force reaches the device's peak (motors clip), or the lateral
  // amplitude is still growing: second half of the window > growth_ratio x first half.
  double growth_ratio = 1.5;
  // An axis oscillates when its detrended position crosses the mean at least this often in the
  // window (two full cycles); otherwise its motion is drift and its amplitude does not count ...
  int min_crossings = 4;
  // ... unless the motors did more net work than this in the window: then slow motion is a slow
  // cycle the loop feeds, not a settling or sinking pen (whose motors resist: negative work). 1 mJ
  // is the passivity controller's reservoir slack, "the most a sampling oscillation may build
  // before the controller answers" (server/passivity.hpp).
  double drift_energy_j = 1e-3;
  // cannot-hold: the continuous-force limit acted in the window and either the push exceeds the
  // device's continuous force (the limit steps the force down from the push: it cannot be held),
  // or the mean penetration exceeds the depth at which the spring holds the push (push / k) by
  // more than this fraction of the period; the excursion limit's 1 mm: that far through the
  // floor the pen rests on no valley.
  double sink_period_fraction = 0.25;

  double stableAmplitudeM() const { return stable_amplitude_counts * encoder_resolution_m; }
};

struct CellMetrics {
  bool finite = true;
  double window_s = 0.0;
  // motion (true state)
  double lateral_pp_m = 0.0;          // detrended peak-to-peak of x over the window
  double lateral_pp_first_m = 0.0;    // same over the first and second halves (growth check)
  double lateral_pp_second_m = 0.0;
  double lateral_rms_m = 0.0;         // detrended RMS of x
  double lateral_offset_m = 0.0;      // mean x - aimed x
  double excursion_m = 0.0;           // max |x - floor x| over the window (not detrended)
  double normal_pp_m = 0.0;           // detrended peak-to-peak of z
  double depth_mean_m = 0.0;          // mean rendered penetration (TickRecord::depth_m)
  double held_depth_m = 0.0;          // push / k: where the spring alone would hold the push
  double push_force_n = 0.0;          // the hand's push
  double continuous_force_n = 0.0;    // the device's continuous force (the safety stage's budget)
  int crossings = 0;                  // crossings of the detrended mean x, one-count dead band
  int normal_crossings = 0;           // the same for z
  double oscillation_hz = 0.0;        // crossings / 2 / window
  // forces (commanded, after safety)
  double lateral_force_pp_n = 0.0;
  double lateral_force_rms_n = 0.0;   // about its mean
  double normal_force_mean_n = 0.0;
  double normal_force_pp_n = 0.0;
  double peak_force_n = 0.0;          // max |F_out| in the window
  double peak_force_run_n = 0.0;      // max |F_out| over the whole cell
  // energy (see the header comment)
  double motor_work_j = 0.0;
  double energy_injected_j = 0.0;
  double injected_power_w = 0.0;      // energy_injected_j / window_s
  // pipeline activity, fraction of window ticks
  double contact_fraction = 0.0;
  double at_peak_fraction = 0.0;           // output at the device's peak force or motors clipped
  double peak_clamp_fraction = 0.0;        // safety cut the request to the peak
  double continuous_limit_fraction = 0.0;  // safety continuous-force (thermal) limit
  double rate_limit_fraction = 0.0;
  double recovery_fraction = 0.0;          // renderer recovery ramp active
  double passivity_active_fraction = 0.0;  // controller damping > 0
  double passivity_dissipated_j = 0.0;     // credited by the controller in the window

  Verdict verdict = Verdict::Stable;
  std::string reason;  // the rule that decided the verdict, with its numbers
};

// One tick's worth of what the window needs.
struct WindowSample {
  double t_s = 0.0;
  Eigen::Vector3d p_m = Eigen::Vector3d::Zero();  // true, plane-local
  Eigen::Vector3d f_out_n = Eigen::Vector3d::Zero();
  double depth_m = 0.0;
  bool in_contact = false;
  bool recovering = false;
  bool at_peak = false;       // the output reached the device's peak force (or the motors clipped)
  bool peak_clamped = false;  // the safety stage cut the REQUEST to the peak (the output may be lower)
  bool continuous_limited = false;
  bool rate_limited = false;
  bool passivity_active = false;
};

// Energy bookkeeping at the window's ends and in between.
struct WindowEnergy {
  double motor_work_j = 0.0;
  double kinetic_start_j = 0.0, kinetic_end_j = 0.0;
  double hand_potential_start_j = 0.0, hand_potential_end_j = 0.0;
  double passivity_dissipated_j = 0.0;
};

// Fills everything but the verdict. `aim_x_m`, `floor_x_m`: plane-local x of the aim and the floor.
CellMetrics measureWindow(const std::vector<WindowSample>& samples, const WindowEnergy& energy, double aim_x_m,
                          double floor_x_m, double encoder_resolution_m, double peak_force_run_n);

// Applies the rules in order: non-finite -> unstable; held down and sunk -> cannot-hold;
// excursion, peak force, growth -> unstable; small amplitude and ripple -> stable; otherwise
// limit-cycle. Sets verdict and reason. m.held_depth_m, push_force_n and continuous_force_n must
// be set.
void classify(CellMetrics& m, const Thresholds& t, double period_m);

}  // namespace thx::srv::stab
