#include "server/capsule_tool.hpp"

#include <algorithm>
#include <cmath>

namespace thx::srv {

namespace {

// A pass that moves the tool less than this (10 nm) ends the tick's passes.
constexpr double kSettledM = 1e-8;

// The rotation vector of q (angle x unit axis), the short way round.
Eigen::Vector3d rotationVector(Eigen::Quaterniond q) {
  if (q.w() < 0.0) q.coeffs() = -q.coeffs();
  const Eigen::AngleAxisd aa(q.normalized());
  return aa.angle() * aa.axis();
}

Eigen::Quaterniond fromRotationVector(const Eigen::Vector3d& v) {
  const double angle = v.norm();
  if (angle < 1e-15) return Eigen::Quaterniond::Identity();
  return Eigen::Quaterniond(Eigen::AngleAxisd(angle, v / angle));
}

Eigen::Vector3d clampedNorm(const Eigen::Vector3d& v, double limit) {
  const double n = v.norm();
  return (limit > 0.0 && n > limit) ? Eigen::Vector3d(v * (limit / n)) : v;
}

}  // namespace

CapsuleToolConfig couplingForServo(const RendererConfig& renderer, double period_s) {
  CapsuleToolConfig c;
  c.stiffness_n_per_m = renderer.stiffness_n_per_m;
  c.damping_ns_per_m = renderer.damping_ns_per_m;
  c.period_s = period_s;
  c.ramp_ticks = int(std::lround(0.5 / period_s));
  return c;
}

CapsuleTool::CapsuleTool(const tex::TexturedSurface& surface, const dev::DeviceSpec& device,
                         const CapsuleToolConfig& config)
    : surface_(&surface), blocks_(surface), device_(device), config_(config) {
  gains_.k_n_per_m = device.max_stiffness_n_per_m > 0.0
                         ? std::min(config.stiffness_n_per_m, device.max_stiffness_n_per_m)
                         : config.stiffness_n_per_m;
  // A device that shows no torque leaves the pen's orientation to the hand: the coupling's turn is
  // the simulation's own then, not limited by what the device renders stably.
  const bool displays_torque = device.peak_torque_nm > 0.0;
  gains_.k_rot_nm_per_rad = displays_torque && device.max_rot_stiffness_nm_per_rad > 0.0
                                ? std::min(config.rot_stiffness_nm_per_rad, device.max_rot_stiffness_nm_per_rad)
                                : config.rot_stiffness_nm_per_rad;
  b_ = config.damping_ns_per_m ? *config.damping_ns_per_m
                              : 2.0 * config.damping_ratio * std::sqrt(gains_.k_n_per_m * config.device_mass_kg);
  if (device.max_damping_ns_per_m > 0.0) b_ = std::min(b_, device.max_damping_ns_per_m);
  b_rot_ = 2.0 * config.damping_ratio * std::sqrt(gains_.k_rot_nm_per_rad * config.device_inertia_kgm2);
}

void CapsuleTool::reset() {
  placed_ = false;
  ticks_ = 0;
  carried_count_ = 0;
}

void CapsuleTool::carryActiveContacts() {
  carried_count_ = 0;
  for (int k = 0; k < solved_contacts_.count && carried_count_ < kMaxCarried; ++k) {
    const ToolContact& c = solved_contacts_.c[std::size_t(k)];
    if (c.has_texel && solved_.lambda_n[std::size_t(k)] > 0.0) carried_[std::size_t(carried_count_++)] = {c.texel_i, c.texel_j};
  }
}

Eigen::Vector3d CapsuleTool::axisOf(const Eigen::Quaterniond& q_local) const { return q_local * Eigen::Vector3d::UnitZ(); }

CapsuleShape CapsuleTool::capsuleAt(const Eigen::Vector3d& centre_local, const Eigen::Quaterniond& q_local) const {
  const Eigen::Vector3d half = 0.5 * config_.length_m * axisOf(q_local);
  CapsuleShape c;
  c.a = centre_local - half;
  c.b = centre_local + half;
  c.radius_m = config_.radius_m;
  return c;
}

void CapsuleTool::place(const Eigen::Vector3d& device_centre_local, const Eigen::Quaterniond& device_q_local) {
  // At the device's pose, lifted clear of the surface's top (z = 0) if any of it is below; the
  // coupling brings it down onto the surface while the force ramps in.
  centre_local_ = device_centre_local;
  q_local_ = device_q_local;
  const CapsuleShape c = capsuleAt(centre_local_, q_local_);
  const double lowest = std::min(c.a.z(), c.b.z());
  if (lowest < config_.radius_m) centre_local_.z() += config_.radius_m - lowest;
  placed_ = true;
  ticks_ = 0;
  carried_count_ = 0;
}

ToolOutput CapsuleTool::step(const dev::DeviceState& device) {
  ToolOutput out;
  if (!device.valid) return out;
  const Eigen::Quaterniond plane_q(surface_->mapping().plane_to_world.linear());
  const Eigen::Vector3d p_local = surface_->toLocal(device.p_world);
  const Eigen::Quaterniond q_device = (plane_q.conjugate() * device.q_world).normalized();
  const Eigen::Vector3d c_device = p_local + 0.5 * config_.length_m * axisOf(q_device);
  if (!placed_) place(c_device, q_device);

  const Eigen::Vector3d c_before = centre_local_;
  const Eigen::Quaterniond q_before = q_local_;
  const double half_extent = 0.5 * config_.length_m + config_.radius_m;
  const double skin = 0.1 * surface_->texelSize();
  bool settled = false;
  for (int pass = 0; pass <= config_.passes; ++pass) {
    const Eigen::Vector3d dx_target = c_device - centre_local_;
    const Eigen::Vector3d dtheta_target = rotationVector(q_device * q_local_.conjugate());
    // The motion this pass is bounded by what the search can vouch for. Its contacts are one per
    // feature, the nearest point of each (capsule_contacts.hpp), which stands for the feature
    // only while the tool moves little; so the tool may move freely up to the nearest any texel
    // came (nothing is closer) and then by min_reach_m more, against those contacts. A free pen
    // moves max_step_m a pass, a touching one min_reach_m: it catches up over the next passes and
    // ticks. The solve sees the whole target (its multipliers are the contacts' forces against
    // the whole spring); a motion beyond the allowance is cut back to it.
    // Searched near first (a touching tool needs no more), farther only if nothing is near.
    const double motion = dx_target.norm() + half_extent * dtheta_target.norm();
    const CapsuleShape here = capsuleAt(centre_local_, q_local_);
    double reach = std::min(motion, config_.min_reach_m) + skin;
    findCapsuleContacts(*surface_, here, reach, contacts_, &blocks_);
    out.texels_examined += contacts_.texels_examined;
    if (contacts_.nearest_gap_m >= reach && motion > config_.min_reach_m) {
      // Nothing near: how far the nearest texel is (one read a texel), then the contacts within
      // that and min_reach_m more.
      const double far = std::min(motion, config_.max_step_m) + skin;
      findCapsuleClearance(*surface_, here, far, contacts_, &blocks_);
      out.texels_examined += contacts_.texels_examined;
      reach = std::min(far, std::max(0.0, contacts_.nearest_gap_m) + config_.min_reach_m + skin);
      findCapsuleContacts(*surface_, here, reach, contacts_, &blocks_);
      out.texels_examined += contacts_.texels_examined;
    }
    const double clearance = std::max(0.0, std::min(contacts_.nearest_gap_m, reach));
    const double allowed = std::min({config_.max_step_m, reach, clearance + config_.min_reach_m});
    if (pass == config_.passes) break;  // the last search only measures where the tool ended
    for (int k = 0; k < carried_count_; ++k)
      addCarriedContact(*surface_, here, carried_[std::size_t(k)][0], carried_[std::size_t(k)][1], contacts_);
    solved_ = projectToolMotion(dx_target, dtheta_target, contacts_, centre_local_, gains_, config_.solver);
    solved_contacts_ = contacts_;
    carryActiveContacts();
    out.solver_sweeps += solved_.sweeps;
    const double moved = solved_.dx.norm() + half_extent * solved_.dtheta.norm();
    const double cut = moved > allowed ? allowed / moved : 1.0;
    centre_local_ += cut * solved_.dx;
    q_local_ = (fromRotationVector(cut * solved_.dtheta) * q_local_).normalized();
    // A pass that barely moved the tool leaves its contacts where they were: searching again
    // would find the same ones (a resting or slowly sliding tool: one search and one solve a tick).
    if (cut == 1.0 && moved < kSettledM) {
      settled = true;
      break;
    }
  }
  out.penetration_m = 0.0;
  if (settled) {
    // Where the last solve left its contacts, linearised (the motion was under kSettledM).
    for (int i = 0; i < solved_contacts_.count; ++i) {
      const ToolContact& c = solved_contacts_.c[std::size_t(i)];
      const double moved_towards = c.normal.dot(solved_.dx + solved_.dtheta.cross(c.point - (centre_local_ - solved_.dx)));
      out.penetration_m = std::max(out.penetration_m, -(c.gap_m + moved_towards));
    }
  } else {
    for (int i = 0; i < contacts_.count; ++i)
      out.penetration_m = std::max(out.penetration_m, -contacts_.c[std::size_t(i)].gap_m);
  }

  // The contacts' forces from the last solve: at equilibrium they balance the coupling's spring.
  Eigen::Vector3d f_contacts = Eigen::Vector3d::Zero();
  Eigen::Vector3d t_contacts = Eigen::Vector3d::Zero();
  for (int i = 0; i < solved_contacts_.count; ++i) {
    const ToolContact& c = solved_contacts_.c[std::size_t(i)];
    const Eigen::Vector3d f = solved_.lambda_n[std::size_t(i)] * c.normal;
    f_contacts += f;
    t_contacts += (c.point - centre_local_).cross(f);
  }
  const Eigen::Vector3d spring_f = gains_.k_n_per_m * (centre_local_ - c_device);
  const Eigen::Vector3d spring_t = gains_.k_rot_nm_per_rad * rotationVector(q_local_ * q_device.conjugate());

  // Damping on the relative motion of the tool and the device (their centres).
  const Eigen::Vector3d w_device = plane_q.conjugate() * device.w_world;
  const Eigen::Vector3d v_device =
      plane_q.conjugate() * (device.v_world + device.w_world.cross(plane_q * (c_device - p_local)));
  const bool moved_before = ticks_ > 0;
  const Eigen::Vector3d v_tool = moved_before ? Eigen::Vector3d((centre_local_ - c_before) / config_.period_s)
                                              : v_device;
  const Eigen::Vector3d w_tool =
      moved_before ? Eigen::Vector3d(rotationVector(q_local_ * q_before.conjugate()) / config_.period_s) : w_device;
  const Eigen::Vector3d force_local = spring_f + b_ * (v_tool - v_device);
  const Eigen::Vector3d torque_local = spring_t + b_rot_ * (w_tool - w_device);

  ++ticks_;
  const double ramp = config_.ramp_ticks > 0 ? std::min(1.0, double(ticks_) / double(config_.ramp_ticks)) : 1.0;
  out.coupling_torque_world = plane_q * torque_local;
  out.force_world = clampedNorm(ramp * (plane_q * force_local), device_.peak_force_n);
  out.torque_world = device_.peak_torque_nm > 0.0
                         ? clampedNorm(ramp * out.coupling_torque_world, device_.peak_torque_nm)
                         : Eigen::Vector3d::Zero();
  out.contact_force_world = plane_q * f_contacts;
  out.contact_torque_world = plane_q * t_contacts;
  out.tool_orientation_world = plane_q * q_local_;
  out.tool_tip_world = surface_->toWorld(capsuleAt(centre_local_, q_local_).a);
  const ToolContacts& final_contacts = settled ? solved_contacts_ : contacts_;
  for (int i = 0; i < final_contacts.count; ++i)
    if (settled ? solved_.lambda_n[std::size_t(i)] > 0.0 : final_contacts.c[std::size_t(i)].gap_m <= skin) ++out.contacts;
  out.in_contact = out.contacts > 0;
  return out;
}

RenderOutput CapsuleTool::renderOutput(const ToolOutput& tool, const dev::DeviceState& device) const {
  RenderOutput out;
  out.in_contact = tool.in_contact;
  out.proxy_held = tool.in_contact;
  out.force_world = tool.force_world;
  out.proxy_world = tool.tool_tip_world;
  const Eigen::Vector3d tip_local = surface_->toLocal(tool.tool_tip_world);
  const tex::SurfacePoint under = surface_->at(tip_local.x(), tip_local.y());
  out.p_proj_world = surface_->toWorld({tip_local.x(), tip_local.y(), 0.0});
  out.uv = under.uv;
  long long i = 0, j = 0;
  surface_->texelContaining(tip_local.x(), tip_local.y(), i, j);
  out.texel = {int(std::clamp(i, -(1LL << 30), 1LL << 30)), int(std::clamp(j, -(1LL << 30), 1LL << 30))};
  out.n_geom_world = surface_->directionToWorld(Eigen::Vector3d::UnitZ());
  out.n_sampled_world = surface_->directionToWorld(under.n_local);
  out.relief_depth_m = -under.height_m;
  out.f_normal_n = tool.contact_force_world.dot(out.n_geom_world);
  out.depth_m = std::max(0.0, (tool.tool_tip_world - device.p_world).dot(out.n_geom_world));
  out.v_tangent_world = device.v_world - device.v_world.dot(out.n_geom_world) * out.n_geom_world;
  out.tangent_world = surface_->directionToWorld(Eigen::Vector3d::UnitX());
  out.bitangent_world = surface_->directionToWorld(Eigen::Vector3d::UnitY());
  return out;
}

}  // namespace thx::srv
