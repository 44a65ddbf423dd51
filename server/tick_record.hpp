#pragma once
// One servo tick as it leaves the real-time thread: to the publisher (LCM), the flight recorder
// and the analysis tools. Plain data, fixed size, copied by value.
#include <cstdint>

namespace thx::srv {

enum TickFault : std::uint32_t {
  kFaultNone = 0,
  kFaultInvalidReading = 1u << 0,   // the device reported valid = false or non-finite values
  kFaultMissedTicks = 1u << 1,      // more consecutive missed ticks than the policy allows
  kFaultNonFiniteForce = 1u << 2,   // rendering produced a non-finite force (safety zeroed it)
  kFaultForceBudget = 1u << 3,      // the safety stage's continuous-force budget ran out (|F| limited)
};

struct TickRecord {
  // timing
  std::int64_t tick = 0;
  std::int64_t deadline_ns = 0;
  std::int64_t wake_latency_ns = 0;
  std::int64_t compute_ns = 0;
  std::int32_t missed = 0;
  // device
  double p_world[3] = {};
  double v_world[3] = {};
  double q_world[4] = {1, 0, 0, 0};  // w, x, y, z (device_state_t's order; DeviceSnapshot::q_world_xyzw is VRPN's)
  std::uint32_t buttons = 0;
  bool valid = true;
  // contact (see RenderOutput)
  bool in_contact = false;
  bool recovering = false;
  std::int8_t num_planes = 0;
  std::uint32_t active_mask = 0;
  std::int32_t texel_i = 0, texel_j = 0;
  double uv[2] = {};
  double proxy_world[3] = {};
  bool proxy_held = false;  // proxy_world is on the surface with the tip below it (RenderOutput)
  double p_proj_world[3] = {};
  double n_geom_world[3] = {0, 0, 1};
  double n_sampled_world[3] = {0, 0, 1};
  double depth_m = 0.0;
  double relief_depth_m = 0.0;
  double f_normal_n = 0.0;
  double v_tangent_world[3] = {};
  double plane_n_world[4][3] = {};
  double plane_d_m[4] = {};
  std::int32_t triangle = -1;  // RenderOutput::triangle (a mesh's; -1 on the plane)
  double barycentric[3] = {};
  double tangent_world[3] = {1, 0, 0};
  double bitangent_world[3] = {0, 1, 0};
  // forces, N, world frame, in pipeline order
  double f_render[3] = {};   // texture proxy spring
  double f_client[3] = {};   // from clients (physics: pen-object contact)
  double f_external[3] = {}; // effects commanded by VRPN apps (planes, fields, buzz)
  double f_passive[3] = {};  // after the passivity controller
  double f_out[3] = {};      // after the safety stage: what the device was told
  double pc_energy_j = 0.0;
  double pc_damping_ns_per_m = 0.0;
  std::uint32_t safety_flags = 0;
  std::uint32_t faults = 0;  // TickFault bits raised this tick
  std::uint32_t fault_latched = 0;  // one TickFault bit: the first fault since the last reset (0: none)
  std::uint32_t fault_resets = 0;   // FaultReset::seq of the last reset the servo applied (0: none yet)
  // scene switches (Servo::surfaceSwap)
  std::uint32_t scene_swaps = 0;  // swaps applied since start; this tick is the first on the new
                                  // surface when it is one more than the last tick's
  double scene_gain = 1.0;        // the switch ramp on the scene's force (1: no switch under way)
  // A pen with extent (device.tool: capsule; server/capsule_tool.hpp); zero for the point pen.
  bool tool = false;             // the capsule rendered this tick (proxy_world is its tip's centre)
  double tool_q_world[4] = {1, 0, 0, 0};  // the tool's orientation, w, x, y, z
  std::int32_t tool_contacts = 0;
  double tool_penetration_m = 0.0;
  double tau_render[3] = {};     // N m, the coupling's torque for the device (0: it shows none)
  double tau_out[3] = {};        // what the device was told: tau_render x the scene's and the safety stage's gains
};

}  // namespace thx::srv
