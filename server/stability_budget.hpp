#pragma once
// Stability budget as data (docs/design.md §5): the rendered stiffness is a fraction of the
// device's vendor maximum, checked at configuration time against the sampled-wall passivity bound
// of Colgate & Schenkel,
//     K <= 2 (b - |B|) / T     (b: device physical damping, B: virtual damping, T: period).
//
// Contract: configuration time only (allocates strings); never called from the servo tick.
// Malformed input (non-finite, negative, zero period) throws thx::Error naming the
// field, value and expectation. Exceeding the bound is a *finding*, not malformed input: with the
// small physical damping of a real device the bound sits far below the vendor maxima (the vendor
// figure counts on the user's hand adding damping; a Desktop needs b >= 0.5 N s/m for 1000 N/m),
// so by default it is a warning and the passivity controller carries the risk; BoundPolicy::Strict
// makes it an error. The policy is the caller's, not hard-coded here. A shipped scene always
// exceeds it (b = 0.005 N s/m is below any useful virtual damping), so callers print the finding
// only when asked (hapticd --verbose), with `explanation`, never on every run.
#include <string>
#include <vector>

#include "device/haptic_device.hpp"

namespace thx::srv {

enum class BoundPolicy { Warn, Strict };

struct StabilityRequest {
  double stiffness_fraction = 0.5;        // of the device's max stiffness
  double virtual_damping_ns_per_m = 0.0;  // B, rendered along the proxy normal
  double period_s = 1e-3;
  BoundPolicy policy = BoundPolicy::Warn;
};

struct StabilityBudget {
  double stiffness_n_per_m = 0.0;  // K = fraction x vendor max
  double stiffness_fraction = 0.0;
  double vendor_max_stiffness_n_per_m = 0.0;
  double physical_damping_ns_per_m = 0.0;  // b
  double virtual_damping_ns_per_m = 0.0;   // B
  double period_s = 0.0;
  double bound_n_per_m = 0.0;  // 2 (b - |B|) / T; <= 0 when |B| >= b
  // K T / 2 + |B|: the physical damping b that would make K passive.
  double required_physical_damping_ns_per_m = 0.0;
  bool within_bound = false;
  bool ok = false;  // false only for errors (Strict policy, or settings no policy accepts)
  std::vector<std::string> warnings;
  std::vector<std::string> errors;
  std::string message;  // the bound check in words, with its numbers
  // What the check means for this device, in plain words, with where to read more; set when the
  // stiffness exceeds the bound (hapticd --verbose prints it beside `message`).
  std::string explanation;
};

StabilityBudget checkStabilityBudget(const dev::DeviceSpec& spec, const StabilityRequest& request);

// Everything the check found, one line each (the message, its explanation, the other warnings);
// what hapticd --verbose prints at start and on each scene switch.
std::vector<std::string> budgetReport(const StabilityBudget& budget);

}  // namespace thx::srv
