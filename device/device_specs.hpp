#pragma once
// Device specs the server's stability budget and safety stage start from. device/ cannot see
// scenes/device_models.hpp, so the one spec the simulator needs is repeated here; the numbers
// must agree with that table (docs/scenes.md §device models).
#include "device/haptic_device.hpp"

namespace thx::dev {

// PHANToM Desktop: peak force, stiffness, damping and workspace from CHAI3D 3.3.0's table
// (docs/scenes.md "Device models"). Continuous force is the project's 15 %-of-peak
// assumption (scenes::kContinuousForceFraction): 1.185 N. Resolution 0.023 mm is the commonly
// quoted vendor figure [unverified]. Physical damping is an assumption, see the .cpp.
DeviceSpec phantomDesktopSpec();

// A simulated 6-DOF pen for tests and benchmarks of torque (issue 30): the Desktop's force figures
// with torque added. Its torque figures are this project's choice, of the order of a 6-DOF
// PHANToM's (a few hundred mN·m), not a vendor's table.
DeviceSpec simulated6DofSpec();

}  // namespace thx::dev
