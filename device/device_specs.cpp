#include "device/device_specs.hpp"

namespace thx::dev {

namespace {
// Same fraction as scenes::kContinuousForceFraction (device/ may not include scenes/).
constexpr double kContinuousForceFraction = 0.15;
}  // namespace

DeviceSpec phantomDesktopSpec() {
  DeviceSpec s;
  s.model = "phantom_desktop";
  s.peak_force_n = 7.9;
  s.continuous_force_n = kContinuousForceFraction * s.peak_force_n;  // 1.185 N
  s.max_stiffness_n_per_m = 1000.0;
  s.max_damping_ns_per_m = 5.0;
  s.workspace_radius_m = 0.10;
  s.position_resolution_m = 2.3e-5;
  // Physical (mechanism) damping b of the passivity bound K <= 2 (b - |B|) / T. A PHANToM is
  // built to be backdriven with almost no viscous drag (capstan drives, no gearbox), so b is
  // a few mN·s/m: an assumption of that order, not a measurement. Consequence, on purpose: the
  // bare device is passive only up to 2 b / T = 10 N/m at 1 kHz; the vendor's 1000 N/m works
  // because the hand holding the pen adds damping. A pen let go on a stiff wall buzzes.
  s.physical_damping_ns_per_m = 0.005;
  return s;
}

DeviceSpec simulated6DofSpec() {
  DeviceSpec s = phantomDesktopSpec();
  s.model = "simulated_6dof";
  s.peak_torque_nm = 0.2;
  s.max_rot_stiffness_nm_per_rad = 2.0;
  return s;
}

}  // namespace thx::dev
