// The stability budget with PHANToM Desktop numbers: stiffness as a fraction of the vendor
// maximum, the sampled-wall bound K <= 2 (b - |B|) / T, the warn/strict policy, and the message.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "device/device_specs.hpp"
#include "server/stability_budget.hpp"

namespace test_stability_budget {

using namespace thx;
using srv::BoundPolicy;
using srv::StabilityBudget;
using srv::StabilityRequest;

namespace {

// PHANToM Desktop: CHAI3D's 1000 N/m and 5 N s/m; b = 5 mN s/m is the project's assumed
// mechanism damping (device/device_specs.cpp), not a measurement.
dev::DeviceSpec desktop() { return dev::phantomDesktopSpec(); }

StabilityRequest request(double fraction, double damping = 0.0,
                         BoundPolicy policy = BoundPolicy::Warn) {
  StabilityRequest r;
  r.stiffness_fraction = fraction;
  r.virtual_damping_ns_per_m = damping;
  r.period_s = 1e-3;
  r.policy = policy;
  return r;
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

std::string rejection(const dev::DeviceSpec& spec, const StabilityRequest& r) {
  try {
    srv::checkStabilityBudget(spec, r);
  } catch (const thx::Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(StabilityBudget, DesktopAtSixTenthsExceedsTheBoundAndWarnsByDefault) {
  const StabilityBudget s = srv::checkStabilityBudget(desktop(), request(0.6));
  EXPECT_DOUBLE_EQ(s.stiffness_n_per_m, 600.0);
  EXPECT_DOUBLE_EQ(s.stiffness_fraction, 0.6);
  EXPECT_DOUBLE_EQ(s.vendor_max_stiffness_n_per_m, 1000.0);
  EXPECT_NEAR(s.bound_n_per_m, 10.0, 1e-9);                      // 2 x 0.005 / 0.001
  EXPECT_NEAR(s.required_physical_damping_ns_per_m, 0.3, 1e-12);  // 600 x 0.001 / 2
  EXPECT_FALSE(s.within_bound);
  EXPECT_TRUE(s.ok);
  EXPECT_TRUE(s.errors.empty());
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_EQ(s.warnings[0], s.message);
  EXPECT_TRUE(contains(s.message, "stiffness 600 N/m (0.6 of 1000) exceeds the sampled-wall bound "
                                  "2(b−|B|)/T = 10 N/m for b = 0.005 N·s/m, B = 0 N·s/m, T = 1 ms"))
      << s.message;
  EXPECT_TRUE(contains(s.message, "b ≥ 0.3 N·s/m")) << s.message;
  // In plain words: b alone passes 10 N/m; the hand and the passivity controller carry the rest.
  EXPECT_TRUE(contains(s.explanation, "passes only stiffness up to 10 N/m")) << s.explanation;
  EXPECT_TRUE(contains(s.explanation, "hand's damping and the passivity controller")) << s.explanation;
  const std::vector<std::string> report = srv::budgetReport(s);
  ASSERT_EQ(report.size(), 2u);  // the message and its explanation; the warning is the message
  EXPECT_EQ(report[1], s.explanation);
}

TEST(StabilityBudget, ShippedDampingMakesTheBoundNegativeAndTheExplanationSaysSo) {
  // Every shipped scene: 0.6 of the Desktop's 1000 N/m with B = 1 N s/m against b = 0.005 N s/m.
  const StabilityBudget s = srv::checkStabilityBudget(desktop(), request(0.6, 1.0));
  EXPECT_NEAR(s.bound_n_per_m, -1990.0, 1e-9);
  EXPECT_NEAR(s.required_physical_damping_ns_per_m, 1.3, 1e-12);
  EXPECT_TRUE(contains(s.explanation, "b = 0.005 N·s/m is smaller than the rendered damping |B| = 1 N·s/m"))
      << s.explanation;
  EXPECT_TRUE(contains(s.explanation, "no stiffness at all meets it")) << s.explanation;
  EXPECT_TRUE(contains(s.explanation, "it needs 1.3 N·s/m of damping in all")) << s.explanation;
  // Within the bound there is nothing to explain.
  EXPECT_TRUE(srv::checkStabilityBudget(desktop(), request(0.008)).explanation.empty());
}

TEST(StabilityBudget, StrictPolicyMakesTheSameFindingAnError) {
  const StabilityBudget s =
      srv::checkStabilityBudget(desktop(), request(0.6, 0.0, BoundPolicy::Strict));
  EXPECT_FALSE(s.ok);
  ASSERT_EQ(s.errors.size(), 1u);
  EXPECT_EQ(s.errors[0], s.message);
  EXPECT_TRUE(s.warnings.empty());
}

TEST(StabilityBudget, VendorMaximumNeedsHalfANewtonSecondPerMetreOfPhysicalDamping) {
  // docs/design.md §5 (K <= 2(b - |B|)/T): at T = 1 ms, K = 1000 N/m needs b >= 0.5 N s/m before
  // virtual damping.
  const StabilityBudget s = srv::checkStabilityBudget(desktop(), request(1.0));
  EXPECT_NEAR(s.required_physical_damping_ns_per_m, 0.5, 1e-12);
  EXPECT_FALSE(s.within_bound);
  // With that much physical damping the vendor maximum is exactly on the bound.
  dev::DeviceSpec damped = desktop();
  damped.physical_damping_ns_per_m = 0.5;
  const StabilityBudget d = srv::checkStabilityBudget(damped, request(1.0));
  EXPECT_NEAR(d.bound_n_per_m, 1000.0, 1e-9);
  EXPECT_TRUE(d.within_bound);
  EXPECT_TRUE(d.warnings.empty());
  EXPECT_TRUE(contains(d.message, "is within")) << d.message;
}

TEST(StabilityBudget, SmallStiffnessIsWithinTheBound) {
  const StabilityBudget s =
      srv::checkStabilityBudget(desktop(), request(0.008, 0.0, BoundPolicy::Strict));
  EXPECT_DOUBLE_EQ(s.stiffness_n_per_m, 8.0);
  EXPECT_TRUE(s.within_bound);
  EXPECT_TRUE(s.ok);
  EXPECT_TRUE(s.warnings.empty());
  EXPECT_TRUE(s.errors.empty());
  EXPECT_TRUE(contains(s.message, "stiffness 8 N/m (0.008 of 1000) is within")) << s.message;
}

TEST(StabilityBudget, VirtualDampingSpendsTheSameBudget) {
  // B = 4 mN s/m leaves 1 mN s/m: the bound drops from 10 to 2 N/m.
  const StabilityBudget s = srv::checkStabilityBudget(desktop(), request(0.002, 0.004));
  EXPECT_NEAR(s.bound_n_per_m, 2.0, 1e-9);
  EXPECT_TRUE(s.within_bound);  // K = 2 N/m
  EXPECT_NEAR(s.required_physical_damping_ns_per_m, 0.005, 1e-15);

  // |B| counts, whatever its sign; more than b alone is already active.
  const StabilityBudget neg = srv::checkStabilityBudget(desktop(), request(0.002, -0.01));
  EXPECT_NEAR(neg.bound_n_per_m, -10.0, 1e-9);
  EXPECT_FALSE(neg.within_bound);
  bool mentions_negative = false, mentions_exceeds_b = false;
  for (const std::string& w : neg.warnings) {
    mentions_negative |= contains(w, "negative");
    mentions_exceeds_b |= contains(w, "exceeds the physical damping");
  }
  EXPECT_TRUE(mentions_negative);
  EXPECT_TRUE(mentions_exceeds_b);

  // Above the device's maximum damping: a finding (warning, or error when strict).
  const StabilityBudget over =
      srv::checkStabilityBudget(desktop(), request(0.0, 6.0, BoundPolicy::Strict));
  EXPECT_FALSE(over.ok);
  bool mentions_max = false;
  for (const std::string& e : over.errors) mentions_max |= contains(e, "device maximum 5 N·s/m");
  EXPECT_TRUE(mentions_max);
}

TEST(StabilityBudget, OtherFindings) {
  // Above the vendor maximum: allowed for experiments (a warning) unless strict.
  EXPECT_TRUE(srv::checkStabilityBudget(desktop(), request(1.2)).ok);
  EXPECT_FALSE(srv::checkStabilityBudget(desktop(), request(1.2, 0.0, BoundPolicy::Strict)).ok);

  // Zero stiffness renders nothing.
  const StabilityBudget zero = srv::checkStabilityBudget(desktop(), request(0.0));
  EXPECT_TRUE(zero.within_bound);
  ASSERT_EQ(zero.warnings.size(), 1u);
  EXPECT_TRUE(contains(zero.warnings[0], "render no force"));

  // Unknown physical damping: the bound is zero, said so.
  dev::DeviceSpec unknown = desktop();
  unknown.physical_damping_ns_per_m = 0.0;
  bool mentions_unknown = false;
  for (const std::string& w : srv::checkStabilityBudget(unknown, request(0.5)).warnings) {
    mentions_unknown |= contains(w, "b = 0 (unknown?)");
  }
  EXPECT_TRUE(mentions_unknown);

  // A slower loop than the vendor's 1 kHz: the bound halves and the vendor figure is not for it.
  StabilityRequest slow = request(0.005);
  slow.period_s = 2e-3;
  const StabilityBudget s = srv::checkStabilityBudget(desktop(), slow);
  EXPECT_NEAR(s.bound_n_per_m, 5.0, 1e-9);
  bool mentions_period = false;
  for (const std::string& w : s.warnings) mentions_period |= contains(w, "servo period 2 ms");
  EXPECT_TRUE(mentions_period);
  EXPECT_TRUE(contains(s.message, "T = 2 ms")) << s.message;
}

TEST(StabilityBudget, MalformedInputIsRejectedNamingTheField) {
  EXPECT_TRUE(contains(rejection(desktop(), request(std::nan(""))), "stiffness_fraction = nan"));
  EXPECT_TRUE(contains(rejection(desktop(), request(-0.1)), "stiffness_fraction = -0.1"));
  EXPECT_TRUE(contains(rejection(desktop(), request(0.5, HUGE_VAL)), "virtual_damping_ns_per_m"));
  StabilityRequest zero_period = request(0.5);
  zero_period.period_s = 0.0;
  EXPECT_TRUE(contains(rejection(desktop(), zero_period), "period_s = 0"));
  dev::DeviceSpec no_max = desktop();
  no_max.max_stiffness_n_per_m = 0.0;
  const std::string what = rejection(no_max, request(0.5));
  EXPECT_TRUE(contains(what, "device 'phantom_desktop' max_stiffness_n_per_m = 0")) << what;
  EXPECT_TRUE(contains(what, "expected")) << what;
  dev::DeviceSpec negative_b = desktop();
  negative_b.physical_damping_ns_per_m = -1.0;
  EXPECT_TRUE(contains(rejection(negative_b, request(0.5)), "physical_damping_ns_per_m = -1"));
}

}  // namespace test_stability_budget
