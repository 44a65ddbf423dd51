#pragma once
// One device's pen as a frame draws it, from a live or a recorded device_state_t: the tip, the
// proxy (held on the surface while the tip is below it), the device's orientation (a capsule
// tool's shaft lies along its +z) and whose pen it is, for its colour (pen_colours.hpp). Plain
// data: the replay library, the live view and the drawing share it.
#include <Eigen/Core>
#include <Eigen/Geometry>

namespace thx::visual {

struct PenView {
  Eigen::Vector3d tip_world = Eigen::Vector3d::Zero();
  Eigen::Vector3d proxy_world = Eigen::Vector3d::Zero();  // = tip_world unless proxy_held
  bool proxy_held = false;                                // device_state_t FLAG_PROXY_HELD
  int device = 0;  // its index in hello_t.device_names (0 for a one-device session's)
  Eigen::Quaterniond q_world = Eigen::Quaterniond::Identity();  // device_state_t.q_world, normalised
};

}  // namespace thx::visual
