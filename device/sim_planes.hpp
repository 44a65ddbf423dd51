#pragma once
// OutputMode::Planes for the simulated PHANToM: the device renders the commanded plane proxies
// itself, as a plane-rendering PHANToM server does, so the servo can be tested against either
// kind of device.
//
// Each plane n.x = d (n outward) pushes with max(0, k depth - b (v.n)) n while the tip is below it
// (depth = d - n.x > 0): a spring-damper that never pulls. Evaluated at the INTEGRATION rate from
// the TRUE state, which is kinder than a real server (it renders at its own 1 kHz from encoder
// readings). Plane friction (mu_static, mu_dynamic) is ignored. Non-finite planes are skipped.
// Real-time safe.
#include <Eigen/Core>

#include "device/haptic_device.hpp"
#include "device/sim_dynamics.hpp"

namespace thx::dev {

Eigen::Vector3d planeForce(const DeviceCommand& command, const SimBodyState& s);

}  // namespace thx::dev
