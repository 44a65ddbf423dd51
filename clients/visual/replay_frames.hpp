#pragma once
// A recorded hapticd session (`hapticd --record FILE`, an LCM log: server/session_log.hpp) as
// frames: one every 1/rate_hz of recorded time (tick time = (tick - first tick) / servo_hz), each
// with every drawn device's pen (tip and proxy) where that device's latest state at or before it
// put it, and, when the log holds THX_PHYSICS_POSES (`physics-client --replay-log S --record OUT`
// writes them into a copy of the session on the same clock), the bodies where the latest poses
// at or before that device state's utime put them. Deterministic: the frames depend on the log
// alone, never on how fast they are drawn.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <string>
#include <vector>

#include "clients/visual/pen_view.hpp"

namespace thx::visual {

struct ReplayFrame {
  // The first pen: of the lowest device index drawn that has a state by then.
  std::int64_t tick = 0;  // its device state's servo tick
  double t_s = 0.0;       // the frame's time from the first recorded tick
  Eigen::Vector3d tip_world = Eigen::Vector3d::Zero();
  Eigen::Vector3d proxy_world = Eigen::Vector3d::Zero();  // = tip_world unless proxy_held
  bool proxy_held = false;                                // device_state_t FLAG_PROXY_HELD
  std::vector<Eigen::Isometry3d> bodies;  // body i = the scene's objects[i]; empty: no poses yet (at rest)
  int device = 0;                         // the first pen's device (0 for a one-device session's)
  Eigen::Quaterniond q_world = Eigen::Quaterniond::Identity();  // the first pen's device orientation
  std::vector<PenView> other_pens;        // the other devices' pens, in index order
};

// Every pen of a frame, the first one first.
std::vector<PenView> pensOf(const ReplayFrame& frame);

// The pens are devices `devices`' (their indices in the recorded hellos' device_names), the other
// devices' states passed over; none (empty) takes every state as the one pen of a one-device
// session (client::loggedDevice says which, thx_client/logged_devices.hpp). A device's pen
// appears from its first state on; the frames run from the first recorded tick of any of them to
// the last.
// Throws thx::Error (Config) naming the file and event: not an LCM log, no THX_DEVICE_STATE
// events (of one of the devices), an event that does not decode, a non-finite position, a
// device's ticks that do not increase, a physics_poses_t with num_bodies out of range or a
// non-finite pose.
std::vector<ReplayFrame> replayFrames(const std::string& log_path, double servo_hz, double rate_hz,
                                      const std::vector<int>& devices = {});

}  // namespace thx::visual
