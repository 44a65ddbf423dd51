#pragma once
// A recorded hapticd session (`hapticd --record FILE`, an LCM log: server/session_log.hpp) as
// frames: one every 1/rate_hz of recorded time (tick time = (tick - first tick) / servo_hz), each
// with the pen (tip and proxy) where the latest device state at or before it put it, and, when the
// log holds THX_PHYSICS_POSES (`physics-client --replay-log S --record OUT` writes them into a copy
// of the session on the same clock), the bodies where the latest poses at or before that device
// state's utime put them. Deterministic: the frames depend on the log alone, never on how fast
// they are drawn.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace thx::visual {

struct ReplayFrame {
  std::int64_t tick = 0;  // the device state's servo tick
  double t_s = 0.0;       // the frame's time from the first recorded tick
  Eigen::Vector3d tip_world = Eigen::Vector3d::Zero();
  Eigen::Vector3d proxy_world = Eigen::Vector3d::Zero();  // = tip_world unless proxy_held
  bool proxy_held = false;                                // device_state_t FLAG_PROXY_HELD
  std::vector<Eigen::Isometry3d> bodies;  // body i = the scene's objects[i]; empty: no poses yet (at rest)
};

// The pen is device `device`'s (its index in the recorded hellos' device_names), the other
// devices' states passed over; nullopt takes every state: a one-device session's
// (client::loggedDevice says which, thx_client/logged_devices.hpp).
// Throws thx::Error (Config) naming the file and event: not an LCM log, no THX_DEVICE_STATE
// events (of that device), an event that does not decode, a non-finite position, ticks that do
// not increase, a physics_poses_t with num_bodies out of range or a non-finite pose.
std::vector<ReplayFrame> replayFrames(const std::string& log_path, double servo_hz, double rate_hz,
                                      std::optional<int> device = std::nullopt);

}  // namespace thx::visual
