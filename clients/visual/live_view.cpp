#include "clients/visual/live_view.hpp"

#include <cmath>

namespace thx::visual {

std::vector<PenView> pensOf(const LiveView& view) {
  std::vector<PenView> pens;
  if (view.pen) pens.push_back(*view.pen);
  pens.insert(pens.end(), view.other_pens.begin(), view.other_pens.end());
  return pens;
}

PenView penViewOf(const thx_msgs::device_state_t& s) {
  PenView p;
  p.device = s.device;
  p.tip_world = Eigen::Vector3d(s.p_world[0], s.p_world[1], s.p_world[2]);
  p.proxy_held = (s.flags & thx_msgs::device_state_t::FLAG_PROXY_HELD) != 0;
  p.proxy_world = p.proxy_held ? Eigen::Vector3d(s.proxy_world[0], s.proxy_world[1], s.proxy_world[2]) : p.tip_world;
  const Eigen::Quaterniond q(s.q_world[0], s.q_world[1], s.q_world[2], s.q_world[3]);
  if (q.coeffs().allFinite() && q.norm() > 1e-6) p.q_world = q.normalized();  // else upright
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
  return liveViewOf(state ? std::vector<thx_msgs::device_state_t>{*state} : std::vector<thx_msgs::device_state_t>{}, poses);
}

LiveView liveViewOf(const std::vector<thx_msgs::device_state_t>& states,
                    const std::optional<thx_msgs::physics_poses_t>& poses) {
  LiveView v;
  for (const thx_msgs::device_state_t& s : states) {
    if (!Eigen::Vector3d(s.p_world[0], s.p_world[1], s.p_world[2]).allFinite()) continue;
    if (v.pen) v.other_pens.push_back(penViewOf(s));
    else v.pen = penViewOf(s);
  }
  if (poses) v.bodies = bodiesOf(*poses);
  return v;
}

namespace {
bool samePen(const PenView& a, const PenView& b) {
  return a.tip_world == b.tip_world && a.proxy_world == b.proxy_world && a.proxy_held == b.proxy_held &&
         a.device == b.device && a.q_world.coeffs() == b.q_world.coeffs();
}
}  // namespace

bool sameView(const LiveView& a, const LiveView& b) {
  const std::vector<PenView> pens_a = pensOf(a), pens_b = pensOf(b);
  if (pens_a.size() != pens_b.size() || a.bodies.size() != b.bodies.size()) return false;
  for (std::size_t i = 0; i < pens_a.size(); ++i) {
    if (!samePen(pens_a[i], pens_b[i])) return false;
  }
  for (std::size_t i = 0; i < a.bodies.size(); ++i) {
    if (a.bodies[i].matrix() != b.bodies[i].matrix()) return false;
  }
  return true;
}

}  // namespace thx::visual
