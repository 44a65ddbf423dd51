#include "server/tick_messages.hpp"

#include "server/safety.hpp"

namespace thx::srv {

namespace {
template <std::size_t N>
void copy(double (&dst)[N], const double (&src)[N]) {
  for (std::size_t k = 0; k < N; ++k) dst[k] = src[k];
}
}  // namespace

std::int32_t wireFaultCode(std::uint32_t tick_fault) {
  using D = thx_msgs::device_state_t;
  switch (tick_fault) {
    case kFaultInvalidReading: return D::FAULT_DEVICE_IO;
    case kFaultMissedTicks: return D::FAULT_MISSED_TICKS;
    case kFaultNonFiniteForce: return D::FAULT_NONFINITE_FORCE;
    case kFaultForceBudget: return D::FAULT_FORCE_BUDGET;
    default: return D::FAULT_NONE;
  }
}

std::int32_t wireFaultMask(std::uint32_t tick_faults) {
  std::int32_t mask = 0;
  for (std::uint32_t bit = 1; bit != 0 && bit <= tick_faults; bit <<= 1) {
    if (tick_faults & bit) mask |= std::int32_t{1} << wireFaultCode(bit);
  }
  return mask & ~std::int32_t{1};  // an unknown bit maps to FAULT_NONE: no bit for it
}

void toDeviceState(const TickRecord& r, bool simulated, thx_msgs::device_state_t& d) {
  using D = thx_msgs::device_state_t;
  d.utime = r.deadline_ns / 1000;
  d.tick = r.tick;
  copy(d.p_world, r.p_world);
  copy(d.q_world, r.q_world);
  copy(d.v_world, r.v_world);
  for (double& w : d.w_world) w = 0.0;  // the devices we drive report no angular velocity
  d.buttons = std::int32_t(r.buttons);
  copy(d.f_cmd_world, r.f_out);
  for (double& t : d.tau_cmd_world) t = 0.0;  // 3-DOF output
  std::int32_t flags = 0;
  if (!(r.safety_flags & (kSafetyDisengaged | kSafetyShutDown))) flags |= D::FLAG_ENGAGED;
  if (r.safety_flags & (kSafetyEngaging | kSafetyRampingOut)) flags |= D::FLAG_RAMPING;
  if (r.safety_flags & kSafetyClampMask) flags |= D::FLAG_SAFETY_CLAMP;
  if (r.in_contact) flags |= D::FLAG_IN_CONTACT;
  if (r.missed > 0) flags |= D::FLAG_MISSED_TICK;
  if (r.f_client[0] != 0.0 || r.f_client[1] != 0.0 || r.f_client[2] != 0.0) flags |= D::FLAG_CLIENT_FORCE;
  if (simulated) flags |= D::FLAG_SIMULATED;
  if (r.faults) flags |= D::FLAG_FAULT;
  if (r.scene_gain < 1.0) flags |= D::FLAG_SCENE_SWITCHING;
  if (r.proxy_held) flags |= D::FLAG_PROXY_HELD;
  d.flags = flags;
  d.flags_seen = flags;
  d.fault_code = wireFaultCode(r.fault_latched);
  d.fault_mask = wireFaultMask(r.faults);
  // Not held (or no reading): the proxy is the tip, exactly, so a client may compare them.
  copy(d.proxy_world, r.proxy_held ? r.proxy_world : r.p_world);
}

void toContact(const TickRecord& r, thx_msgs::contact_t& c) {
  c.utime = r.deadline_ns / 1000;
  c.tick = r.tick;
  c.in_contact = r.in_contact;
  c.num_planes = r.num_planes;
  c.surface_id = 0;
  c.texel_i = r.texel_i;
  c.texel_j = r.texel_j;
  copy(c.p_proj_world, r.p_proj_world);
  copy(c.uv, r.uv);
  copy(c.n_geom_world, r.n_geom_world);
  copy(c.n_sampled_world, r.n_sampled_world);
  c.depth = r.depth_m;
  c.relief_depth = r.relief_depth_m;
  for (int i = 0; i < 4; ++i) {
    copy(c.plane_n_world[i], r.plane_n_world[i]);
    c.plane_d[i] = r.plane_d_m[i];
  }
  c.f_normal = r.f_normal_n;
  for (int k = 0; k < 3; ++k) c.f_normal_world[k] = r.f_normal_n * r.plane_n_world[0][k];
  copy(c.v_tangent_world, r.v_tangent_world);
  c.triangle = r.triangle;
  copy(c.barycentric, r.barycentric);
  copy(c.tangent_world, r.tangent_world);
  copy(c.bitangent_world, r.bitangent_world);
}

}  // namespace thx::srv
