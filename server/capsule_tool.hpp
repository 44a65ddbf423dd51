#pragma once
// A pen with extent (issue 30): the stylus as a capsule, its shaft and its tip, on a textured plane,
// rendered by a virtual coupling (Colgate; McNeely et al. 1999; Otaduy and Lin 2006; CHAI3D's
// 04-Bullet-tool): a 6-DOF spring-damper between the device's pose and a simulated tool that never
// enters the surface.
//
// Geometry: the device's point is the centre of the tip's ball; the shaft runs from it along the
// pen's axis, the device orientation's +z (a pen held upright with the identity), for length_m; the
// ball's radius is the shaft's. The tool's centre is the middle of that segment, and torque is
// taken about it.
//
// Each tick (step()):
//  1. The tool moves from where it was towards the device's pose as far as the surface lets it:
//     contacts are found around the tool within the distance it may move (capsule_contacts.hpp), the
//     closest allowed motion in the coupling's metric is solved (coupling_projection.hpp), and the
//     contacts are found again at the new pose, up to `passes` times (3; fewer once a pass barely
//     moves the tool), so the rotation's linearisation does not leave the shaft in the surface.
//  2. The coupling's wrench on the device: F = k (c_tool - c_device) + b (v_tool - v_device) and
//     tau = k_rot rotvec(q_tool q_device^-1) + b_rot (w_tool - w_device), about the tool's centre.
//     k and k_rot are capped by the device's stiffest stable values; b and b_rot critically damp the
//     device's mass and inertia on them (b = 2 sqrt(k m)), or b is the configured damping
//     (damping_ns_per_m: hapticd's choice), b held at the device's damping limit when that is
//     lower; damping acts on the relative motion, so a free pen feels nothing.
//  3. Ramped in over ramp_ticks from the first step (and after reset()), clamped to the device's
//     peak force and torque (direction kept). A device without torque (peak_torque_nm = 0, every
//     3-DOF PHANToM) is given the force only; the torque is still reported.
//
// Real-time safe: no allocation, no locks; the work is bounded by kMaxToolContacts contacts,
// `passes` passes and the solver's sweeps. Plane-local computation, world-frame inputs and outputs.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <optional>

#include "device/haptic_device.hpp"
#include "server/capsule_contacts.hpp"
#include "server/coupling_projection.hpp"
#include "server/proxy_renderer.hpp"
#include "textures/textured_surface.hpp"

namespace thx::srv {

struct CapsuleToolConfig {
  double length_m = 0.10;  // the shaft's axis, tip ball centre to the back end
  double radius_m = 0.002;
  double stiffness_n_per_m = 600.0;        // capped by the device's max_stiffness_n_per_m
  double rot_stiffness_nm_per_rad = 0.5;   // capped by the device's max_rot_stiffness_nm_per_rad (0: none)
  // The moving mass and inertia the coupling's damping is critical for (a PHANToM's pen and arm as
  // the hand leaves them; an assumption of the right order, as in docs/design.md's device model).
  double device_mass_kg = 0.045;
  double device_inertia_kgm2 = 2e-5;
  double damping_ratio = 1.0;
  // Set: the coupling's damping (N s/m) instead of damping_ratio's, still capped by the device's
  // limit. hapticd sets the scene's virtual damping (device.damping, as the point pen's spring):
  // critical damping of 45 g on 600 N/m is 10.4 N s/m, held at the Desktop's 5, and 5 N s/m on the
  // velocity of quantised encoders (one 23 um count a 1 ms tick is 23 mm/s) buzzes 0.24 N p-p at
  // rest in the stability map's V-valleys (docs/hapticd.md).
  std::optional<double> damping_ns_per_m;
  int ramp_ticks = 500;  // 0.5 s at 1 kHz
  double period_s = 1e-3;
  int passes = 3;
  // The farthest the tool moves in one pass (its centre plus its ends' turn): the contacts are
  // searched that far around it, so a device far away (a fast stroke, a pen placed inside the
  // relief) costs a bounded search; 5 mm at 1 kHz and three passes: 15 m/s in free space.
  double max_step_m = 0.005;
  // Beyond the nearest texel's distance the tool moves at most this much more in one pass, held by
  // the contacts found (one per feature): 0.25 mm, three passes a tick: 0.75 m/s along a surface.
  double min_reach_m = 2.5e-4;
  ProjectionSettings solver;
};

// The coupling as a servo at period_s renders it beside the point pen: the renderer's stiffness and
// virtual damping as the coupling's (the device caps them again), its force ramped in over 0.5 s.
// The shape and the turning stiffness stay the defaults, for the caller to set.
CapsuleToolConfig couplingForServo(const RendererConfig& renderer, double period_s);

struct ToolOutput {
  Eigen::Vector3d force_world = Eigen::Vector3d::Zero();   // to send to the device
  Eigen::Vector3d torque_world = Eigen::Vector3d::Zero();  // to send (zero for a force-only device)
  Eigen::Vector3d coupling_torque_world = Eigen::Vector3d::Zero();  // about the tool's centre, before clamping
  Eigen::Vector3d contact_force_world = Eigen::Vector3d::Zero();    // sum of the contacts' forces on the tool
  Eigen::Vector3d contact_torque_world = Eigen::Vector3d::Zero();   // their torque about the tool's centre
  Eigen::Vector3d tool_tip_world = Eigen::Vector3d::Zero();         // the tip ball's centre
  Eigen::Quaterniond tool_orientation_world = Eigen::Quaterniond::Identity();
  int contacts = 0;          // touching after the last pass (multiplier > 0)
  int texels_examined = 0;   // over every pass
  int solver_sweeps = 0;     // over every pass
  double penetration_m = 0.0;  // the deepest contact left at the final pose (> 0: inside)
  bool in_contact = false;
};

class CapsuleTool {
 public:
  CapsuleTool(const tex::TexturedSurface& surface, const dev::DeviceSpec& device, const CapsuleToolConfig& config);

  ToolOutput step(const dev::DeviceState& device);
  // The tick as the point pen's renderer reports it, for the servo's record and the clients (the
  // tool's tip stands for the proxy): the force, the tip, where on the texture the tip is over,
  // the contacts' force along the surface normal, the spring's length along it, and the device's
  // velocity along the surface (the tool slides with it). No plane proxies: the servo sends the
  // force. Real-time safe.
  RenderOutput renderOutput(const ToolOutput& tool, const dev::DeviceState& device) const;
  // Forget the tool: the next step puts it at the device's pose (or as near as the surface lets it
  // from above) and ramps in again.
  void reset();

  double stiffness() const { return gains_.k_n_per_m; }
  double rotStiffness() const { return gains_.k_rot_nm_per_rad; }
  double damping() const { return b_; }
  double rotDamping() const { return b_rot_; }
  const CapsuleToolConfig& config() const { return config_; }
  // The last solve's contacts (plane-local) and each one's force along its normal (N).
  const ToolContacts& solvedContacts() const { return solved_contacts_; }
  const PoseStep& lastSolve() const { return solved_; }
  // The tool's centre in the surface's frame.
  Eigen::Vector3d centreLocal() const { return centre_local_; }

 private:
  CapsuleShape capsuleAt(const Eigen::Vector3d& centre_local, const Eigen::Quaterniond& q_local) const;
  Eigen::Vector3d axisOf(const Eigen::Quaterniond& q_local) const;
  void place(const Eigen::Vector3d& device_centre_local, const Eigen::Quaterniond& device_q_local);

  const tex::TexturedSurface* surface_;
  ReliefBlockHeights blocks_;
  dev::DeviceSpec device_;
  CapsuleToolConfig config_;
  CouplingGains gains_;
  double b_ = 0.0;
  double b_rot_ = 0.0;
  bool placed_ = false;
  long long ticks_ = 0;
  Eigen::Vector3d centre_local_ = Eigen::Vector3d::Zero();
  Eigen::Quaterniond q_local_ = Eigen::Quaterniond::Identity();
  ToolContacts contacts_;
  ToolContacts solved_contacts_;
  // The texels whose contacts held (multiplier > 0) in the last solve, carried into the next
  // pass's contacts (addCarriedContact()).
  static constexpr int kMaxCarried = 8;
  std::array<std::array<long long, 2>, kMaxCarried> carried_{};
  int carried_count_ = 0;
  void carryActiveContacts();
  PoseStep solved_;
};

}  // namespace thx::srv
