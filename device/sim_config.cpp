#include "device/sim_config.hpp"

#include <cmath>
#include <string>

#include "device/hand_script_detail.hpp"

namespace thx::dev {

namespace {

[[noreturn]] void fail(const char* field, const std::string& problem, const char* expected, const std::string& value) {
  throw DeviceError(std::string("SimPhantomConfig.") + field + ": " + problem + "; expected " + expected + ", got '" +
                    value + "'");
}

std::string num(double v) { return detail::formatNumber(v); }

void positive(const char* field, double v, const char* expected) {
  if (!std::isfinite(v) || !(v > 0.0)) fail(field, std::isfinite(v) ? "out of range" : "not finite", expected, num(v));
}

void nonNegative(const char* field, double v, const char* expected) {
  if (!std::isfinite(v) || v < 0.0) fail(field, std::isfinite(v) ? "out of range" : "not finite", expected, num(v));
}

}  // namespace

int stepsPerTick(const SimPhantomConfig& c) {
  return int(std::int64_t(c.integration_hz) * c.servo_period_ns / 1'000'000'000);
}

void validate(const SimPhantomConfig& c) {
  positive("spec.peak_force_n", c.spec.peak_force_n, "a force > 0 N");
  nonNegative("spec.physical_damping_ns_per_m", c.spec.physical_damping_ns_per_m, "a damping >= 0 N·s/m");
  if (c.servo_period_ns <= 0 || c.servo_period_ns > 1'000'000'000)
    fail("servo_period_ns", "out of range", "a period in (0, 1e9] ns", std::to_string(c.servo_period_ns));
  if (c.integration_hz <= 0) fail("integration_hz", "out of range", "a rate > 0 Hz", std::to_string(c.integration_hz));
  const std::int64_t product = std::int64_t(c.integration_hz) * c.servo_period_ns;
  if (product % 1'000'000'000 != 0 || stepsPerTick(c) < 10)
    fail("integration_hz", "not a whole number >= 10 of steps per servo tick",
         "integration_hz * servo period a whole number >= 10 (10000 Hz at a 1 ms tick)",
         std::to_string(c.integration_hz) + " Hz with a " + std::to_string(c.servo_period_ns) + " ns tick");
  positive("encoder_resolution_m", c.encoder_resolution_m, "a resolution > 0 m");
  positive("device_mass_kg", c.device_mass_kg, "a mass > 0 kg");
  nonNegative("friction_n", c.friction_n, "a force >= 0 N");
  positive("friction_velocity_scale_m_per_s", c.friction_velocity_scale_m_per_s, "a speed > 0 m/s");
  positive("hand_mass_kg", c.hand_mass_kg, "a mass > 0 kg");
  nonNegative("hand_stiffness_n_per_m", c.hand_stiffness_n_per_m, "a stiffness >= 0 N/m");
  nonNegative("hand_damping_ns_per_m", c.hand_damping_ns_per_m, "a damping >= 0 N·s/m");
  if (!(c.hand_push_normal_stiffness_fraction >= 0.0 && c.hand_push_normal_stiffness_fraction <= 1.0))
    fail("hand_push_normal_stiffness_fraction", "out of range", "a fraction in [0, 1]",
         num(c.hand_push_normal_stiffness_fraction));
  if (!c.plane_to_world.matrix().allFinite() ||
      !(c.plane_to_world.linear().transpose() * c.plane_to_world.linear()).isIdentity(1e-9))
    fail("plane_to_world", "not a rigid transform", "a finite rotation and translation", "a non-orthonormal matrix");
  if (c.surface_height && !std::isfinite(c.surface_height->top()))
    fail("surface_height", "top not finite", "a surface whose highest point is finite", num(c.surface_height->top()));
  if (!(c.watchdog_decay >= 0.0 && c.watchdog_decay <= 1.0))
    fail("watchdog_decay", "out of range", "a factor in [0, 1]", num(c.watchdog_decay));
  if (c.watchdog_hold_ticks < 0)
    fail("watchdog_hold_ticks", "out of range", "a tick count >= 0", std::to_string(c.watchdog_hold_ticks));

  // The explicit integrator must resolve the hand spring and the viscous part of the damping and
  // friction (sim_dynamics.hpp): otherwise the integrator, not the servo, would be what goes unstable.
  const double dt = 1.0 / c.integration_hz;
  const double mass = c.device_mass_kg + c.hand_mass_kg;
  const double viscous = c.spec.physical_damping_ns_per_m + c.hand_damping_ns_per_m +
                         c.friction_n / c.friction_velocity_scale_m_per_s;
  if (dt * viscous / mass > 0.5)
    fail("integration_hz", "too low for the damping and smoothed friction",
         "dt * (b + hand damping + friction / velocity scale) / mass <= 0.5", num(dt * viscous / mass));
  if (dt * dt * c.hand_stiffness_n_per_m / mass > 0.25)
    fail("integration_hz", "too low for the hand stiffness", "dt^2 * hand stiffness / mass <= 0.25",
         num(dt * dt * c.hand_stiffness_n_per_m / mass));
}

}  // namespace thx::dev
