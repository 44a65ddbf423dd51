#pragma once
// The servo tick: hapticd's hard-real-time heart. THIS FILE AND servo.cpp ARE THE REAL-TIME PATH.
//
// Contract of tick() (docs/design.md §4 rules 1-3):
//  - One blocking device read (tickAt(): a read that does not block, the group's clock having
//    waited: servo_group.hpp), one device write; nothing else blocks. No allocation, no lock, no
//    logging, no system call except the device's pacing sleep (a test proves "no allocation").
//  - Data leaves only through the SPSC ring (publisher), the flight recorder and the device
//    snapshot slot (the VRPN server's reports); data enters only through latest-value slots
//    (client forces; fault resets; external effects, see external_effects.hpp).
//  - Pipeline: read -> render (texture proxy) + client force + external effects (VRPN apps) ->
//    passivity controller -> safety stage -> write. Safety is always last and always on.
//  - Render: the plane's renderer (proxy_renderer.hpp, the fast path), or, while the scene's
//    surface is a textured mesh, that scene's mesh renderer (textured_mesh_renderer.hpp), built
//    and owned off this thread like the scene's texture; or, for a pen with extent (a scene's
//    device.tool: capsule), that scene's capsule tool (capsule_tool.hpp), built and owned the same
//    way. One branch chooses; nothing else differs but the torque. The mesh renderer's work for
//    the ticks after this one (gathering the triangles ahead of the pen) runs after the write.
//  - Torque (the capsule on a device that displays it): the coupling's torque, clamped by the tool
//    to the device's peak, times the scene's gain and the safety stage's gain (its engage and
//    shutdown ramps), and zero whenever the safety stage lets no force through. The passivity
//    controller and the safety stage's force limits act on the force only.
//  - Missed-cycle policy: the pacer realigns to the next period (no catch-up burst); while the
//    servo is away the device holds its last force with decay (its own watchdog). What a gap
//    does then is MissedTickPolicy's decision (server/missed_tick_policy.hpp): ride through it
//    (the safety stage's rate limit restarts from the force the device still held; the passivity
//    observer books the held force's work over the gap), or disengage the safety stage (force
//    off, then the small-force engage and ramp) and freeze the flight recorder for a dump, once
//    per run of disengaging ticks. max_invalid_readings consecutive invalid readings disengage
//    the same way.
//  - Faults latch: every record carries the first fault since the last reset (server start, or a
//    client's reset through faultResetSlot(), applied at the start of the next tick).
//  - Scene switches: a SurfaceSwap offered through surfaceSwap() (built off this thread, owned by
//    its builder, server/scene_switcher.hpp) is taken at a tick boundary; the scene's force (the
//    texture's and the clients') ramps down over scene_ramp_ticks, the renderer is retargeted at
//    zero force, the force ramps up again. Taking, retargeting and completing the handoff neither
//    allocate nor free: the builder frees the old surface once the handoff says it is done. A mesh
//    scene's renderer starts without a proxy: a pen inside the new mesh's solid at the swap feels
//    nothing until it leaves it (a god object never starts inside), so no force can jump.
#include <cstdint>

#include "device/haptic_device.hpp"
#include "server/flight_recorder.hpp"
#include "server/latency_histogram.hpp"
#include "server/missed_tick_policy.hpp"
#include "rt/handoff.hpp"
#include "rt/latest_slot.hpp"
#include "server/capsule_tool.hpp"
#include "server/external_effects.hpp"
#include "server/passivity.hpp"
#include "server/proxy_renderer.hpp"
#include "server/safety.hpp"
#include "rt/spsc_ring.hpp"
#include "server/textured_mesh_renderer.hpp"
#include "server/tick_record.hpp"

namespace thx::srv {

struct ServoConfig {
  MissedTickPolicyConfig missed;  // what a gap does (ServoRig fills it from the device)
  int max_invalid_readings = 3;  // consecutive invalid device readings before a fault
  int client_force_timeout_ticks = 50;  // a client force not refreshed for this long is dropped
  // A scene switch ramps the scene's force down over this many ticks, swaps, and ramps it up over
  // as many (smoothstep both ways, so the force rate has no step either): 0.2 s at 1 kHz, the
  // safety stage's shutdown ramp.
  int scene_ramp_ticks = 200;
};

// Another scene's surface for the renderer, prepared off the servo thread (server/scene_switcher.hpp)
// and kept alive by its builder until Servo::surfaceSwap() reports the swap done and the next
// swap is done with it in turn. Plain data and a pointer: the servo copies, never owns.
struct SurfaceSwap {
  const tex::TexturedSurface* surface = nullptr;
  RendererConfig renderer;
  double stored_energy_stiffness_n_per_m = 0.0;  // the passivity observer's K (the renderer's)
  // A mesh scene: its renderer, fresh (never rendered), owned by the builder like `surface`; the
  // servo renders it instead of the plane until the next swap. nullptr: the plane's renderer,
  // retargeted at `surface` with `renderer`.
  TexturedMeshRenderer* mesh = nullptr;
  // A scene whose device has a capsule tool: that tool, fresh, owned by the builder like `mesh`;
  // the servo renders it instead of the plane's renderer until the next swap.
  CapsuleTool* tool = nullptr;
};

// What a client (the physics client) asks the servo to add to the rendered force.
struct ClientForce {
  double force_world_n[3] = {0, 0, 0};
};

// A client's request to clear the latched fault (server_command_t ACTION_RESET_FAULTS), numbered
// by its one writer (the publisher thread); the servo echoes the last number it applied in
// TickRecord::fault_resets, which is how the writer knows the reset happened.
struct FaultReset {
  std::uint32_t seq = 0;
};

// The newest tick's device state for slower readers (the VRPN server's reports). Plain data.
struct DeviceSnapshot {
  std::int64_t tick = 0;
  std::int64_t deadline_ns = 0;
  double p_world[3] = {};
  double q_world_xyzw[4] = {0, 0, 0, 1};  // VRPN's order (TickRecord::q_world is w, x, y, z)
  double v_world[3] = {};
  double f_out[3] = {};
  double scp_world[3] = {};  // surface contact point: the proxy in contact, else the tip
  std::uint32_t buttons = 0;
  bool valid = false;
};

struct ServoCounters {
  std::uint64_t ticks = 0;
  std::uint64_t missed_ticks = 0;
  std::uint64_t invalid_readings = 0;
  std::uint64_t faults = 0;
  std::uint64_t contact_ticks = 0;
  std::uint64_t client_force_ticks = 0;  // a client's force (e.g. physics-client's pen contact) was non-zero
  // The safety stage passed the force at gain 1, unclamped by its rate limit: neither disengaged,
  // ramping nor restarting after a gap. The pen felt the whole force the scene asked for.
  std::uint64_t full_force_ticks = 0;
  std::uint64_t contact_full_force_ticks = 0;  // of those, in contact
  // The ticks and missed periods from the first full engagement to the shutdown request: what
  // full_force_ticks is a share of (the start-up engage ramp and the shutdown ramp are no loss).
  std::uint64_t service_ticks = 0;
  std::uint64_t service_missed_ticks = 0;
  std::uint64_t service_contact_ticks = 0;  // of service_ticks, in contact
  double max_force_n = 0.0;
};

class Servo {
 public:
  // `mesh`: the first scene's mesh renderer (a mesh scene), else nullptr: the plane's `renderer`.
  // `tool`: the first scene's capsule tool (device.tool: capsule), else nullptr: the point pen.
  Servo(dev::HapticDevice& device, ProxyRenderer& renderer, PassivityController& passivity, SafetyStage& safety,
        FlightRecorder& recorder, rt::SpscRing<TickRecord>& out, const ServoConfig& config,
        TexturedMeshRenderer* mesh = nullptr, CapsuleTool* tool = nullptr);

  // One tick. Returns this tick's record (valid until the next call).
  const TickRecord& tick() { return step(device_.read()); }
  // One tick at a time another clock paced (several devices under one clock: servo_group.hpp):
  // the device is read with readTick(timing), which does not wait; the rest is tick()'s.
  const TickRecord& tickAt(const rt::TickTiming& timing) { return step(device_.readTick(timing)); }
  const dev::HapticDevice& device() const { return device_; }
  dev::HapticDevice& device() { return device_; }  // to open and close it, outside the tick
  const rt::SpscRing<TickRecord>& ring() const { return out_; }  // where its records go

  void requestShutdown() { safety_.requestShutdown(); }
  bool finished() const { return safety_.shutdownComplete(); }

  rt::LatestSlot<ClientForce>& clientForceSlot() { return client_slot_; }
  rt::LatestSlot<FaultReset>& faultResetSlot() { return reset_slot_; }
  // The one way a new scene reaches the servo (see the contract above); one swap in flight.
  rt::Handoff<const SurfaceSwap>& surfaceSwap() { return surface_swap_; }
  // Optional (before the first tick): effects commanded by VRPN apps, added to the force.
  void attachExternalEffects(ExternalEffectRenderer* effects) { external_ = effects; }
  // Optional (before the first tick): from then on every tick also writes a DeviceSnapshot here
  // for a slower reader (the VRPN server). Without a reader nothing is written.
  const rt::LatestSlot<DeviceSnapshot>& publishSnapshots() {
    snapshots_ = true;
    return snapshot_slot_;
  }
  const LatencyHistogram& computeHistogram() const { return compute_hist_; }
  const LatencyHistogram& wakeHistogram() const { return wake_hist_; }
  const ServoCounters& counters() const { return counters_; }
  const MissedTickPolicy& missedTickPolicy() const { return missed_policy_; }
  // The mesh renderer in use (a mesh scene), else nullptr (the plane). Servo thread, or stopped.
  const TexturedMeshRenderer* meshRenderer() const { return mesh_; }
  // The capsule tool in use (device.tool: capsule), else nullptr. Servo thread, or stopped.
  const CapsuleTool* capsuleTool() const { return tool_; }
  // The renderer in use forgets its proxy (after a bad reading; a rig's reset). Servo thread, or stopped.
  void resetRenderer();

 private:
  const TickRecord& step(const dev::DeviceState& state);  // the tick after the device's reading
  std::uint32_t latchFaults(std::uint32_t faults);
  double stepSceneSwitch();  // this tick's scene gain; swaps the renderer at zero force
  void writeSnapshot(const TickRecord& r, const dev::DeviceState& state, const RenderOutput& out,
                     const ExternalOutput& ext, const Eigen::Vector3d& f_out);

  dev::HapticDevice& device_;
  ProxyRenderer& renderer_;
  TexturedMeshRenderer* mesh_ = nullptr;  // renders instead of renderer_ while set
  CapsuleTool* tool_ = nullptr;           // renders instead of both while set
  PassivityController& passivity_;
  SafetyStage& safety_;
  FlightRecorder& recorder_;
  rt::SpscRing<TickRecord>& out_;
  ServoConfig config_;
  MissedTickPolicy missed_policy_;

  rt::LatestSlot<ClientForce> client_slot_;
  ExternalEffectRenderer* external_ = nullptr;
  rt::LatestSlot<DeviceSnapshot> snapshot_slot_;
  bool snapshots_ = false;
  std::uint32_t client_seq_ = 0;
  ClientForce client_force_;
  int client_age_ticks_ = 1 << 30;
  int invalid_run_ = 0;
  rt::LatestSlot<FaultReset> reset_slot_;
  std::uint32_t reset_seq_ = 0;      // LatestSlot's sequence of the last reset read
  std::uint32_t resets_applied_ = 0;  // FaultReset::seq of that reset
  std::uint32_t fault_latched_ = 0;   // TickFault bit, 0: none since the last reset
  enum class SwitchPhase { None, RampDown, RampUp };
  rt::Handoff<const SurfaceSwap> surface_swap_;
  const SurfaceSwap* swap_next_ = nullptr;  // taken, waiting for the ramp down
  SwitchPhase switch_phase_ = SwitchPhase::None;
  int switch_tick_ = 0;
  std::uint32_t scene_swaps_ = 0;
  bool engaged_once_ = false;

  LatencyHistogram compute_hist_;
  LatencyHistogram wake_hist_;
  ServoCounters counters_;
  TickRecord record_;
};

}  // namespace thx::srv
