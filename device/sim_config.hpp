#pragma once
// Configuration of the simulated PHANToM and of the hand holding it. The server fills it from a
// scene (scenes::SimDeviceParams + the surface pose); device/ never sees scenes/.
//
// Defaults: docs/scenes.md §device.sim (assumptions for a PHANToM Desktop in a light pen grip).
#include <Eigen/Geometry>
#include <cstdint>

#include "device/device_specs.hpp"
#include "device/haptic_device.hpp"
#include "device/surface_height.hpp"

namespace thx::dev {

// Deterministic faults by tick index (TickTiming::tick). A window is [from_tick, from_tick + ticks).
struct SimFaults {
  // The reading's p_world and v_world are quiet NaN while valid stays TRUE: a device that lies,
  // which only the server's finite check can catch.
  std::int64_t nan_from_tick = -1;
  std::int64_t nan_ticks = 0;
  // valid = false: p_world holds the last reading delivered, v_world is zero.
  std::int64_t invalid_from_tick = -1;
  std::int64_t invalid_ticks = 0;
};

struct SimPhantomConfig {
  DeviceSpec spec = phantomDesktopSpec();  // peak force clips the motors; physical damping acts
  OutputMode output_mode = OutputMode::Force;

  std::int64_t servo_period_ns = 1'000'000;  // the device's tick
  // Real time: the last spin_ns before each tick spent in a busy wait instead of asleep
  // (rt::Pacer; hapticd --spin-us). Ignored in lock-step; clamped below the period.
  std::int64_t spin_ns = 0;
  int integration_hz = 10'000;               // integration_hz * period must be a whole number >= 10

  double encoder_resolution_m = 2.3e-5;  // position quantum per axis
  double device_mass_kg = 0.045;         // apparent mass of the mechanism at the tip
  double friction_n = 0.06;              // Coulomb friction of the mechanism
  // Coulomb friction is smoothed as F_c tanh(|v| / scale): below the scale it acts as a viscous
  // damper F_c / scale (60 N·s/m by default), which keeps the explicit friction term stable at
  // 10 kHz and stops a resting pen without chattering.
  double friction_velocity_scale_m_per_s = 1e-3;

  double hand_mass_kg = 0.2;  // moves with the pen: the body is m_pen + m_hand
  double hand_stiffness_n_per_m = 300.0;
  double hand_damping_ns_per_m = 3.0;
  // While the hand pushes, it regulates force rather than depth along the normal (a person
  // pressing keeps the force, not the position): the spring's normal component drops to this
  // fraction of hand_stiffness (blended in over the first 0.2 N of push). Without it a stiff
  // hand spring anchored at the surface would cancel part of the push (a 1 N press gave 0.67 N on
  // a 600 N/m wall) and hold the pen above the floor of a deep valley.
  double hand_push_normal_stiffness_fraction = 0.1;
  Eigen::Isometry3d plane_to_world = Eigen::Isometry3d::Identity();  // local z = outward normal
  // The pen's orientation, world frame, as the hand holds it: fixed (the simulated device is 3-DOF:
  // it moves the tip and displays force only). The identity holds a pen with extent upright
  // (server/capsule_tool.hpp: its shaft along +z).
  Eigen::Quaterniond pen_orientation = Eigen::Quaterniond::Identity();
  // A curved surface the hand's script follows (hand_script.hpp): heights in plane_to_world's
  // frame (the script's). Not owned: it must outlive the device. nullptr: the plane z = 0.
  const SurfaceHeight* surface_height = nullptr;

  // Device watchdog: with no write() for a device tick the last output is held x decay^n for
  // n = 1..hold ticks, then zero.
  double watchdog_decay = 0.5;
  int watchdog_hold_ticks = 2;

  bool lockstep = true;  // VirtualClock (deterministic); false: MonotonicClock, real time
  SimFaults faults;
};

// Throws DeviceError naming the field, the value and what was expected.
void validate(const SimPhantomConfig& config);

// Integration steps per servo tick (validated config).
int stepsPerTick(const SimPhantomConfig& config);

}  // namespace thx::dev
