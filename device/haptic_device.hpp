#pragma once
// HapticDevice: what the servo loop talks to. Real devices (a PHANToM behind VRPN) and the
// simulated PHANToM honour the same contract, so the servo cannot tell them apart.
//
// Contract (the device is the clock):
//  - read() blocks until the device's next tick and returns the state sampled at that tick,
//    with the tick's timing. It is the only blocking call of the servo tick.
//  - write() hands over this tick's output and returns immediately. A device that renders
//    forces applies DeviceCommand::force_world_n; a device that renders planes itself (a
//    PHANToM behind a VRPN server) applies DeviceCommand::planes.
//  - Neither allocates, locks or logs: both run inside the real-time tick.
//  - If write() is not called for a tick (the servo missed it), the device holds the last output
//    with decay for a couple of ticks, then outputs zero (its own watchdog).
//  - open() and close() run outside the real-time loop and may throw DeviceError.
//  - Several devices under one servo clock (server/servo_group.hpp): the group waits for the tick
//    and reads each device with readTick(), which returns at once with the state for that tick.
//    A device that can be read so says so with sharesClock(); the group refuses the others.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "base/error.hpp"
#include "rt/pacer.hpp"

namespace thx::dev {

// A device that cannot be opened or used (an unreachable VRPN server, a bad replay file).
class DeviceError : public thx::Error {
 public:
  explicit DeviceError(const std::string& what) : thx::Error(Kind::Io, what) {}
};

// What a device model can do; the servo's stability budget and safety stage start from it.
struct DeviceSpec {
  std::string model;
  double peak_force_n = 0.0;
  double continuous_force_n = 0.0;
  double max_stiffness_n_per_m = 0.0;  // stable wall stiffness at 1 kHz (vendor figure)
  double max_damping_ns_per_m = 0.0;
  double workspace_radius_m = 0.0;
  double position_resolution_m = 0.0;
  double physical_damping_ns_per_m = 0.0;  // b of the passivity bound K <= 2 (b - |B|) / T
  // Torque a 6-DOF device displays about its pen (0: force only, as every 3-DOF PHANToM), and the
  // stiffest rotational coupling it renders stably. A pen with extent (server/capsule_tool.hpp)
  // sends torque only to a device that has some.
  double peak_torque_nm = 0.0;
  double max_rot_stiffness_nm_per_rad = 0.0;
};

struct DeviceState {
  rt::TickTiming timing;                                  // tick index, deadline, wake-up, missed ticks
  Eigen::Vector3d p_world = Eigen::Vector3d::Zero();  // m, pen tip
  Eigen::Quaterniond q_world = Eigen::Quaterniond::Identity();
  Eigen::Vector3d v_world = Eigen::Vector3d::Zero();  // m/s (device's estimate)
  Eigen::Vector3d w_world = Eigen::Vector3d::Zero();  // rad/s
  std::uint32_t buttons = 0;
  bool valid = true;  // false: the device could not deliver a fresh, trustworthy sample
};

// A plane proxy as a plane-rendering device understands it: n.x = d (world frame, n unit,
// outward), with its own spring, damping and friction.
struct PlaneProxy {
  Eigen::Vector3d n_world = Eigen::Vector3d::UnitZ();
  double d_m = 0.0;
  double k_n_per_m = 0.0;
  double b_ns_per_m = 0.0;
  double mu_static = 0.0;
  double mu_dynamic = 0.0;
};

inline constexpr int kMaxPlanes = 4;

struct DeviceCommand {
  Eigen::Vector3d force_world_n = Eigen::Vector3d::Zero();  // force-rendering devices
  // A device that displays torque (DeviceSpec::peak_torque_nm > 0) renders it too; others ignore it.
  Eigen::Vector3d torque_world_nm = Eigen::Vector3d::Zero();
  std::array<PlaneProxy, kMaxPlanes> planes{};               // plane-rendering devices
  int num_planes = 0;
  bool forces_enabled = false;  // false: output zero whatever the fields say
};

enum class OutputMode { Force, Planes };

class HapticDevice {
 public:
  virtual ~HapticDevice() = default;
  virtual const DeviceSpec& spec() const = 0;
  virtual OutputMode outputMode() const = 0;
  virtual void open() = 0;
  virtual void close() = 0;
  virtual DeviceState read() = 0;
  virtual void write(const DeviceCommand& command) = 0;
  // The state at a tick another clock paced (`timing`: the group's tick, deadline, wake and missed
  // periods); does not wait. Same contract as read() otherwise. Only where sharesClock(): the
  // default answers an invalid reading, which the servo treats as a faulty device.
  virtual bool sharesClock() const { return false; }
  virtual DeviceState readTick(const rt::TickTiming& timing) {
    DeviceState s;
    s.timing = timing;
    s.valid = false;
    return s;
  }
};

}  // namespace thx::dev
