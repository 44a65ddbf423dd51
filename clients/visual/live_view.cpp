#include "clients/visual/live_view.hpp"

#include <cmath>

namespace thx::visual {

PenView penViewOf(const thx_msgs::device_state_t& s) {
  PenView p;
  p.tip_world = Eigen::Vector3d(s.p_world[0], s.p_world[1], s.p_world[2]);
  p.proxy_held = (s.flags & thx_msgs::device_state_t::FLAG_PROXY_HELD) != 0;
  p.proxy_world = p.proxy_held ? Eigen::Vector3d(s.proxy_world[0], s.proxy_world[1], s.proxy_world[2]) : p.tip_world;
  return p;
}

namespace {
Eigen::Vector3d positionOf(const thx_msgs::physics_poses_t& m, int i) {
  return {m.p_world[i][0], m.p_world[i][1], m.p_world[i][2]};
}
Eigen::Quaterniond rotationOf(const thx_msgs::physics_poses_t& m, int i) {
  return {m.q_world[i][0], m.q_world[i][1], m.q_world[i][2], m.q_world[i][3]};
}
}  // namespace

std::string posesProblem(const thx_msgs::physics_poses_t& m) {
  constexpr int kMax = thx_msgs::physics_poses_t::MAX_BODIES;
  if (m.num_bodies < 0 || m.num_bodies > kMax)
    return "num_bodies " + std::to_string(m.num_bodies) + "; expected 0.." + std::to_string(kMax);
  for (int i = 0; i < m.num_bodies; ++i) {
    const Eigen::Quaterniond q = rotationOf(m, i);
    if (!positionOf(m, i).allFinite() || !q.coeffs().allFinite() || std::abs(q.norm() - 1.0) > 1e-3)
      return "body " + std::to_string(i) + " has a non-finite position or a quaternion that is not unit";
  }
  return "";
}

std::vector<Eigen::Isometry3d> bodiesOf(const thx_msgs::physics_poses_t& m) {
  if (!posesProblem(m).empty()) return {};
  std::vector<Eigen::Isometry3d> out;
  for (int i = 0; i < m.num_bodies; ++i) {
    const Eigen::Vector3d p = positionOf(m, i);
    const Eigen::Quaterniond q = rotationOf(m, i);
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.translate(p);
    pose.rotate(q.normalized());
    out.push_back(pose);
  }
  return out;
}

LiveView liveViewOf(const std::optional<thx_msgs::device_state_t>& state,
                    const std::optional<thx_msgs::physics_poses_t>& poses) {
  LiveView v;
  if (state && Eigen::Vector3d(state->p_world[0], state->p_world[1], state->p_world[2]).allFinite())
    v.pen = penViewOf(*state);
  if (poses) v.bodies = bodiesOf(*poses);
  return v;
}

bool sameView(const LiveView& a, const LiveView& b) {
  if (a.pen.has_value() != b.pen.has_value() || a.bodies.size() != b.bodies.size()) return false;
  if (a.pen && (a.pen->tip_world != b.pen->tip_world || a.pen->proxy_world != b.pen->proxy_world ||
                a.pen->proxy_held != b.pen->proxy_held))
    return false;
  for (std::size_t i = 0; i < a.bodies.size(); ++i) {
    if (a.bodies[i].matrix() != b.bodies[i].matrix()) return false;
  }
  return true;
}

}  // namespace thx::visual
