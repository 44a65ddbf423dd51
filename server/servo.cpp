#include "server/servo.hpp"

#include <algorithm>
#include <cmath>

#include "rt/clock.hpp"

namespace thx::srv {

namespace {

// Real CPU time even in lock-step (the device's clock may be virtual).
std::int64_t monotonicNs() { return rt::monotonicNowNs(); }

void put(double (&dst)[3], const Eigen::Vector3d& v) {
  dst[0] = v.x();
  dst[1] = v.y();
  dst[2] = v.z();
}

}  // namespace

Servo::Servo(dev::HapticDevice& device, ProxyRenderer& renderer, PassivityController& passivity,
             SafetyStage& safety, FlightRecorder& recorder, rt::SpscRing<TickRecord>& out, const ServoConfig& config,
             TexturedMeshRenderer* mesh, CapsuleTool* tool)
    : device_(device),
      renderer_(renderer),
      mesh_(mesh),
      tool_(tool),
      passivity_(passivity),
      safety_(safety),
      recorder_(recorder),
      out_(out),
      config_(config),
      missed_policy_(config.missed) {}

const TickRecord& Servo::step(const dev::DeviceState& state) {
  const std::int64_t t0 = monotonicNs();

  TickRecord& r = record_;
  r = TickRecord{};
  r.tick = state.timing.tick;
  r.deadline_ns = state.timing.deadline_ns;
  r.wake_latency_ns = state.timing.wake_latency_ns;
  r.missed = std::int32_t(state.timing.missed);
  put(r.p_world, state.p_world);
  put(r.v_world, state.v_world);
  r.q_world[0] = state.q_world.w();
  r.q_world[1] = state.q_world.x();
  r.q_world[2] = state.q_world.y();
  r.q_world[3] = state.q_world.z();
  r.buttons = state.buttons;

  FaultReset reset;
  if (reset_slot_.readIfNewer(reset, reset_seq_)) {
    fault_latched_ = 0;
    resets_applied_ = reset.seq;
  }

  const double scene_gain = stepSceneSwitch();

  std::uint32_t faults = 0;
  counters_.missed_ticks += std::uint64_t(state.timing.missed);
  r.valid = state.valid && state.p_world.allFinite() && state.v_world.allFinite();
  const MissedTickDecision gap = missed_policy_.observe(state.timing.missed, state.p_world, r.valid);
  if (gap.fault) faults |= kFaultMissedTicks;
  Eigen::Vector3d f_render = Eigen::Vector3d::Zero();
  Eigen::Vector3d tau_render = Eigen::Vector3d::Zero();
  RenderOutput out;  // no planes unless rendered
  if (r.valid) {
    invalid_run_ = 0;
    if (tool_) {
      const ToolOutput tool = tool_->step(state);
      out = tool_->renderOutput(tool, state);
      tau_render = tool.torque_world;
      r.tool = true;
      r.tool_q_world[0] = tool.tool_orientation_world.w();
      r.tool_q_world[1] = tool.tool_orientation_world.x();
      r.tool_q_world[2] = tool.tool_orientation_world.y();
      r.tool_q_world[3] = tool.tool_orientation_world.z();
      r.tool_contacts = tool.contacts;
      r.tool_penetration_m = tool.penetration_m;
    } else {
      // The force's half now; where the contact is after the force is written (below).
      out = mesh_ ? mesh_->renderForce(state.p_world, state.v_world) : renderer_.renderForce(state.p_world, state.v_world);
    }
    f_render = out.force_world;
    r.in_contact = out.in_contact;
    r.recovering = out.recovering;
    r.num_planes = std::int8_t(out.num_planes);
    r.active_mask = out.active_mask;
    put(r.proxy_world, out.proxy_world);
    r.proxy_held = out.proxy_held;
    r.depth_m = out.depth_m;
    r.f_normal_n = out.f_normal_n;
    for (int i = 0; i < out.num_planes; ++i) {
      put(r.plane_n_world[i], out.planes[std::size_t(i)].n_world);
      r.plane_d_m[i] = out.planes[std::size_t(i)].d_m;
    }
  } else {
    ++counters_.invalid_readings;
    resetRenderer();  // the proxy's history means nothing across a bad reading
    // One fault per episode: a device that stays invalid (an unreachable VRPN server) would
    // otherwise fault, and dump a flight record, on every tick. The force stays off meanwhile:
    // nothing is rendered for an invalid reading (f_env below).
    if (++invalid_run_ == config_.max_invalid_readings) faults |= kFaultInvalidReading;
  }

  ClientForce fresh;
  if (client_slot_.readIfNewer(fresh, client_seq_)) {
    client_force_ = fresh;
    client_age_ticks_ = 0;
  } else if (client_age_ticks_ < (1 << 30)) {
    ++client_age_ticks_;
  }
  Eigen::Vector3d f_client = Eigen::Vector3d::Zero();
  if (client_age_ticks_ <= config_.client_force_timeout_ticks) {
    f_client = Eigen::Vector3d(client_force_.force_world_n[0], client_force_.force_world_n[1],
                               client_force_.force_world_n[2]);
  }

  // The scene's forces ramp through a switch; VRPN apps' effects belong to no scene.
  f_render *= scene_gain;
  f_client *= scene_gain;

  ExternalOutput ext;
  if (external_) ext = external_->render(state.p_world, state.v_world, r.valid);
  const Eigen::Vector3d& f_external = ext.force_world;

  // A device that renders planes itself (a PHANToM behind VRPN) gets the planes; only the client
  // force goes through the force path, or the texture would be rendered twice.
  const bool device_renders_planes = device_.outputMode() == dev::OutputMode::Planes;
  // Nothing acts on a pen whose position we do not know, not even a client force.
  const Eigen::Vector3d f_env = !r.valid               ? Eigen::Vector3d::Zero()
                                : device_renders_planes ? Eigen::Vector3d(f_client + f_external)
                                                        : Eigen::Vector3d(f_render + f_client + f_external);
  if (!f_env.allFinite() || !tau_render.allFinite()) faults |= kFaultNonFiniteForce;
  if (gap.action == MissedTickAction::RideThrough) {
    // The device went on pushing with its held force over the gap: the observer books that work,
    // and the force returns from what the pen last felt, within the safety stage's rate limit.
    if (r.valid) passivity_.observeHeldPeriods(state.v_world, gap.held_periods);
    safety_.restartRateLimitFrom(gap.held_gain);
  }
  const Eigen::Vector3d f_passive = r.valid ? passivity_.apply(f_env, state.v_world) : f_env;
  // Held disengaged for as long as the readings stay invalid (or the policy says so): the zero
  // requests of those ticks must not count as the "small request" that re-engages the force.
  if (gap.action == MissedTickAction::Disengage || (faults & kFaultInvalidReading) ||
      invalid_run_ >= config_.max_invalid_readings) {
    safety_.disengage();
    passivity_.reset();
  }
  const Eigen::Vector3d f_out = safety_.apply(f_passive);
  constexpr std::uint32_t kNotFull = kSafetyDisengaged | kSafetyEngaging | kSafetyRateLimited | kSafetyRampingOut |
                                     kSafetyShutDown | kSafetyNonFinite;
  const bool full_force = safety_.state() == SafetyState::Engaged && !(safety_.flags() & kNotFull);
  if (safety_.state() == SafetyState::Engaged) engaged_once_ = true;
  const bool shutting_down = safety_.state() == SafetyState::RampingOut || safety_.state() == SafetyState::ShutDown;
  if (engaged_once_ && !shutting_down) {
    ++counters_.service_ticks;
    if (r.in_contact) ++counters_.service_contact_ticks;
    counters_.service_missed_ticks += std::uint64_t(state.timing.missed);
    if (full_force) ++counters_.full_force_ticks;
    if (full_force && r.in_contact) ++counters_.contact_full_force_ticks;
  }
  // Not a reason to disengage: the safety stage's answer is the continuous limit itself.
  if (safety_.flags() & kSafetyBudgetExhausted) faults |= kFaultForceBudget;
  passivity_.recordAppliedForce(f_out);

  // The torque follows the force's engage and shutdown ramps, and stops with it.
  const bool force_allowed = !(safety_.flags() & (kSafetyDisengaged | kSafetyShutDown | kSafetyNonFinite));
  const Eigen::Vector3d tau_out = force_allowed && r.valid && tau_render.allFinite()
                                      ? Eigen::Vector3d(tau_render * (scene_gain * safety_.gain()))
                                      : Eigen::Vector3d::Zero();

  dev::DeviceCommand command;
  command.force_world_n = f_out;
  command.torque_world_nm = tau_out;
  if (device_renders_planes) {
    // Planes only while the safety stage lets forces through (engaged or ramping).
    command.forces_enabled = force_allowed;
    command.num_planes = force_allowed ? out.num_planes : 0;
    command.planes = out.planes;
    for (dev::PlaneProxy& plane : command.planes) {
      plane.k_n_per_m *= scene_gain;
      plane.b_ns_per_m *= scene_gain;
    }
  } else {
    command.forces_enabled = f_out.squaredNorm() > 0.0 || tau_out.squaredNorm() > 0.0;
  }
  device_.write(command);
  // What the renderer does not need for this force, after the write, so that it is not between
  // the reading and the force (still inside compute_ns, the tick's whole work): where the contact
  // is, and what the mesh renderer does for the next tick.
  if (r.valid) {
    if (mesh_ && !tool_) {
      mesh_->describeContact(out);
    } else if (!tool_) {
      renderer_.describeContact(out);
    }
    r.texel_i = out.texel.i;
    r.texel_j = out.texel.j;
    r.uv[0] = out.uv.u;
    r.uv[1] = out.uv.v;
    put(r.p_proj_world, out.p_proj_world);
    put(r.n_geom_world, out.n_geom_world);
    put(r.n_sampled_world, out.n_sampled_world);
    r.relief_depth_m = out.relief_depth_m;
    put(r.v_tangent_world, out.v_tangent_world);
    r.triangle = out.triangle;
    put(r.barycentric, out.barycentric);
    put(r.tangent_world, out.tangent_world);
    put(r.bitangent_world, out.bitangent_world);
  }
  if (mesh_ && !tool_) mesh_->prepareNextTick();

  put(r.f_render, f_render);
  put(r.f_client, f_client);
  put(r.f_external, f_external);
  put(r.f_passive, f_passive);
  put(r.f_out, f_out);
  put(r.tau_render, tau_render);
  put(r.tau_out, tau_out);
  r.pc_energy_j = passivity_.energy();
  r.pc_damping_ns_per_m = passivity_.alpha();
  r.safety_flags = safety_.flags();
  r.faults = faults;
  r.fault_latched = latchFaults(faults);
  r.fault_resets = resets_applied_;
  r.scene_swaps = scene_swaps_;
  r.scene_gain = scene_gain;

  ++counters_.ticks;
  if (r.in_contact) ++counters_.contact_ticks;
  if (r.valid && f_client.squaredNorm() > 0.0) ++counters_.client_force_ticks;
  const double f_norm = f_out.norm();
  if (f_norm > counters_.max_force_n) counters_.max_force_n = f_norm;

  const std::int64_t t1 = monotonicNs();
  r.compute_ns = t1 - t0;
  compute_hist_.add(r.compute_ns);
  wake_hist_.add(r.wake_latency_ns);

  if (snapshots_) writeSnapshot(r, state, out, ext, f_out);

  recorder_.record(r);
  if (faults) {
    ++counters_.faults;
    recorder_.freeze(faults, r.tick);
  }
  out_.push(r);
  return r;
}

void Servo::resetRenderer() {
  if (tool_) {
    tool_->reset();
  } else if (mesh_) {
    mesh_->reset();
  } else {
    renderer_.reset();
  }
}

// None -> (a swap offered) RampDown: gain 1 - s(k/N), k = 1..N-1 -> at k = N the renderer takes
// the new surface with gain 0, the passivity observer forgets the old spring's energy, the
// handoff is completed -> RampUp: gain s(k/N), k = 1..N -> None. s is smoothstep.
double Servo::stepSceneSwitch() {
  const int n = std::max(1, config_.scene_ramp_ticks);
  auto smooth = [n](int k) {
    const double p = double(k) / double(n);
    return p * p * (3.0 - 2.0 * p);
  };
  if (switch_phase_ == SwitchPhase::None) {
    swap_next_ = surface_swap_.take();
    if (swap_next_ == nullptr) return 1.0;
    switch_phase_ = SwitchPhase::RampDown;
    switch_tick_ = 0;
  }
  ++switch_tick_;
  if (switch_phase_ == SwitchPhase::RampDown) {
    if (switch_tick_ < n) return 1.0 - smooth(switch_tick_);
    mesh_ = swap_next_->mesh;
    tool_ = swap_next_->tool;
    if (mesh_ == nullptr) renderer_.retarget(*swap_next_->surface, swap_next_->renderer);
    passivity_.setStoredEnergyStiffness(swap_next_->stored_energy_stiffness_n_per_m);
    passivity_.reset();
    swap_next_ = nullptr;
    surface_swap_.complete();
    ++scene_swaps_;
    switch_phase_ = SwitchPhase::RampUp;
    switch_tick_ = 0;
    return 0.0;
  }
  if (switch_tick_ >= n) switch_phase_ = SwitchPhase::None;
  return smooth(switch_tick_);
}

// Keeps the first fault since the last reset. Of several raised in one tick, the one the tick met
// first: the gap before the reading, the reading, the force, the budget after the safety stage.
std::uint32_t Servo::latchFaults(std::uint32_t faults) {
  if (fault_latched_ == 0) {
    for (std::uint32_t bit : {kFaultMissedTicks, kFaultInvalidReading, kFaultNonFiniteForce, kFaultForceBudget}) {
      if (faults & bit) {
        fault_latched_ = bit;
        break;
      }
    }
  }
  return fault_latched_;
}

// The surface contact point is the texture proxy in contact, else an external plane's contact
// point, else the tip (docs/vrpn.md §9: a stock PHANToM reports the tip when free).
void Servo::writeSnapshot(const TickRecord& r, const dev::DeviceState& state, const RenderOutput& out,
                          const ExternalOutput& ext, const Eigen::Vector3d& f_out) {
  DeviceSnapshot snap;
  snap.tick = r.tick;
  snap.deadline_ns = r.deadline_ns;
  std::copy(r.p_world, r.p_world + 3, snap.p_world);
  std::copy(r.v_world, r.v_world + 3, snap.v_world);
  snap.q_world_xyzw[0] = state.q_world.x();
  snap.q_world_xyzw[1] = state.q_world.y();
  snap.q_world_xyzw[2] = state.q_world.z();
  snap.q_world_xyzw[3] = state.q_world.w();
  put(snap.f_out, f_out);
  const Eigen::Vector3d scp = !r.valid          ? Eigen::Vector3d(Eigen::Vector3d::Zero())
                              : out.in_contact  ? out.proxy_world
                              : ext.in_contact  ? ext.scp_world
                                                : state.p_world;
  put(snap.scp_world, scp);
  snap.buttons = r.buttons;
  snap.valid = r.valid;
  snapshot_slot_.write(snap);
}

}  // namespace thx::srv
