#include "server/stability_budget.hpp"

#include "base/number_text.hpp"
#include "base/error.hpp"

#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace thx::srv {
namespace {

[[noreturn]] void reject(const std::string& field, double value, const char* expected) {
  throw thx::Error(thx::Error::Kind::Config, "stability budget: " + field + " = " + numberText(value) + ": expected " +
                              expected);
}

void requireNonNegative(const std::string& field, double value, const char* expected) {
  if (!std::isfinite(value) || value < 0.0) reject(field, value, expected);
}

void validate(const dev::DeviceSpec& spec, const StabilityRequest& r) {
  const std::string device = "device '" + spec.model + "' ";
  if (!std::isfinite(spec.max_stiffness_n_per_m) || spec.max_stiffness_n_per_m <= 0.0) {
    reject(device + "max_stiffness_n_per_m", spec.max_stiffness_n_per_m,
           "a finite stiffness > 0 N/m (the vendor maximum the fraction refers to)");
  }
  requireNonNegative(device + "physical_damping_ns_per_m", spec.physical_damping_ns_per_m,
                     "a finite damping >= 0 N s/m");
  requireNonNegative(device + "max_damping_ns_per_m", spec.max_damping_ns_per_m,
                     "a finite damping >= 0 N s/m");
  requireNonNegative("stiffness_fraction", r.stiffness_fraction,
                     "a finite fraction >= 0 of the device's max stiffness");
  if (!std::isfinite(r.virtual_damping_ns_per_m)) {
    reject("virtual_damping_ns_per_m", r.virtual_damping_ns_per_m, "a finite damping in N s/m");
  }
  if (!std::isfinite(r.period_s) || r.period_s <= 0.0) {
    reject("period_s", r.period_s, "a finite servo period > 0 s");
  }
}

// The finding in words a user can act on: why the bound cannot be met with this device's own
// damping, and what keeps the wall passive instead.
std::string explain(const dev::DeviceSpec& spec, const StabilityBudget& s) {
  const std::string why =
      s.bound_n_per_m <= 0.0
          ? "its mechanism's own damping b = " + numberText(s.physical_damping_ns_per_m) +
                " N·s/m is smaller than the rendered damping |B| = " + numberText(std::fabs(s.virtual_damping_ns_per_m)) +
                " N·s/m, so the bound is negative and no stiffness at all meets it"
          : "its mechanism's own damping b = " + numberText(s.physical_damping_ns_per_m) +
                " N·s/m passes only stiffness up to " + numberText(s.bound_n_per_m) + " N/m";
  return "what this means: the check asks the device alone, with nobody holding it, to absorb the energy a "
         "wall sampled every " + numberText(s.period_s * 1e3) + " ms can create. For the " + spec.model + " " + why +
         ". Like every vendor maximum (" + numberText(s.vendor_max_stiffness_n_per_m) +
         " N/m here), this stiffness counts on the hand holding the stylus: it needs " +
         numberText(s.required_physical_damping_ns_per_m) +
         " N·s/m of damping in all, which any grip adds. The hand's damping and the passivity controller "
         "(on unless --no-passivity) are what keep the wall passive; the check is not a fault and needs no "
         "action. --strict-stability refuses such a scene. More: docs/hapticd.md#stability-budget";
}

}  // namespace

StabilityBudget checkStabilityBudget(const dev::DeviceSpec& spec, const StabilityRequest& request) {
  validate(spec, request);
  StabilityBudget s;
  s.stiffness_fraction = request.stiffness_fraction;
  s.vendor_max_stiffness_n_per_m = spec.max_stiffness_n_per_m;
  s.stiffness_n_per_m = request.stiffness_fraction * spec.max_stiffness_n_per_m;
  s.physical_damping_ns_per_m = spec.physical_damping_ns_per_m;
  s.virtual_damping_ns_per_m = request.virtual_damping_ns_per_m;
  s.period_s = request.period_s;
  const double abs_b = std::fabs(request.virtual_damping_ns_per_m);
  s.bound_n_per_m = 2.0 * (spec.physical_damping_ns_per_m - abs_b) / request.period_s;
  s.required_physical_damping_ns_per_m = s.stiffness_n_per_m * request.period_s / 2.0 + abs_b;
  // The bound also needs b > |B| strictly; K = 0 with |B| = b is the marginal case and passes.
  s.within_bound = s.stiffness_n_per_m <= s.bound_n_per_m;

  const bool strict = request.policy == BoundPolicy::Strict;
  auto finding = [&](const std::string& text) {
    (strict ? s.errors : s.warnings).push_back(text);
  };

  const std::string numbers = " the sampled-wall bound 2(b−|B|)/T = " + numberText(s.bound_n_per_m) +
                              " N/m for b = " + numberText(s.physical_damping_ns_per_m) +
                              " N·s/m, B = " + numberText(s.virtual_damping_ns_per_m) +
                              " N·s/m, T = " + numberText(request.period_s * 1e3) + " ms";
  s.message = "stiffness " + numberText(s.stiffness_n_per_m) + " N/m (" + numberText(s.stiffness_fraction) +
              " of " + numberText(s.vendor_max_stiffness_n_per_m) + ")" +
              (s.within_bound ? " is within" : " exceeds") + numbers;
  if (!s.within_bound) {
    s.message += "; passive only with b ≥ " + numberText(s.required_physical_damping_ns_per_m) +
                 " N·s/m (the vendor maximum assumes the hand adds damping; the passivity "
                 "controller is the remaining guard)";
    finding(s.message);
    s.explanation = explain(spec, s);
  }

  if (spec.physical_damping_ns_per_m == 0.0) {
    s.warnings.push_back("device '" + spec.model +
                         "' has physical damping b = 0 (unknown?): the bound is <= 0 and no "
                         "stiffness can satisfy it; measure b to make the check meaningful");
  }
  if (abs_b > spec.physical_damping_ns_per_m && spec.physical_damping_ns_per_m > 0.0) {
    s.warnings.push_back("virtual damping |B| = " + numberText(abs_b) +
                         " N·s/m exceeds the physical damping b = " +
                         numberText(spec.physical_damping_ns_per_m) +
                         " N·s/m: the sampled damper alone is not passive");
  }
  if (request.virtual_damping_ns_per_m < 0.0) {
    s.warnings.push_back("virtual damping B = " + numberText(request.virtual_damping_ns_per_m) +
                         " N·s/m is negative: it injects energy");
  }
  if (abs_b > spec.max_damping_ns_per_m) {
    finding("virtual damping |B| = " + numberText(abs_b) + " N·s/m exceeds the device maximum " +
            numberText(spec.max_damping_ns_per_m) + " N·s/m");
  }
  if (request.stiffness_fraction == 0.0) {
    s.warnings.push_back("stiffness fraction is 0: surfaces render no force");
  }
  if (request.stiffness_fraction > 1.0) {
    finding("stiffness fraction " + numberText(request.stiffness_fraction) +
            " is above the device maximum " + numberText(spec.max_stiffness_n_per_m) + " N/m");
  }
  if (request.period_s > 1e-3 * (1.0 + 1e-9)) {
    s.warnings.push_back("servo period " + numberText(request.period_s * 1e3) +
                         " ms is longer than the 1 ms the vendor maximum stiffness is quoted for");
  }
  s.ok = s.errors.empty();
  return s;
}

std::vector<std::string> budgetReport(const StabilityBudget& budget) {
  std::vector<std::string> lines{budget.message};
  if (!budget.explanation.empty()) lines.push_back(budget.explanation);
  for (const std::string& w : budget.warnings) {
    if (w != budget.message) lines.push_back(w);
  }
  return lines;
}

}  // namespace thx::srv
