#pragma once
// What one live frame shows, from the newest messages: the pens (device_state_t: tip, proxy, held;
// one per device drawn) and the bodies (physics_poses_t). sameView() decides whether a frame would
// differ from the last one drawn: the live loop skips a frame when nothing moved.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

#include <thx_msgs/device_state_t.hpp>
#include <thx_msgs/physics_poses_t.hpp>

#include "clients/visual/pen_view.hpp"

namespace thx::visual {

struct LiveView {
  std::optional<PenView> pen;             // the first pen; none before the first device state
  std::vector<Eigen::Isometry3d> bodies;  // body i = the scene's objects[i]; empty: at rest
  std::vector<PenView> other_pens;        // the other devices' pens, in the order given
};

// Every pen of a view, the first one first (none before the first device state).
std::vector<PenView> pensOf(const LiveView& view);

// The pen of a device state, its `device` the message's.
PenView penViewOf(const thx_msgs::device_state_t& s);
// What is wrong with a poses message ("" if nothing): num_bodies outside 0..MAX_BODIES, a body
// with a non-finite position or a quaternion far from unit.
std::string posesProblem(const thx_msgs::physics_poses_t& m);
// The bodies of a poses message; none (drawn at rest) when posesProblem() names something.
std::vector<Eigen::Isometry3d> bodiesOf(const thx_msgs::physics_poses_t& m);
LiveView liveViewOf(const std::optional<thx_msgs::device_state_t>& state,
                    const std::optional<thx_msgs::physics_poses_t>& poses);
// Several devices' pens, one per state (the newest of each device, in index order); a state with
// a non-finite tip is left out.
LiveView liveViewOf(const std::vector<thx_msgs::device_state_t>& states,
                    const std::optional<thx_msgs::physics_poses_t>& poses);

// Exact comparison: the same messages give the same frame, anything else draws a new one.
bool sameView(const LiveView& a, const LiveView& b);

}  // namespace thx::visual
