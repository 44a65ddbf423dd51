#pragma once
// Force effects commanded by external apps (VRPN clients: vrpn_ForceDevice Plane, Plane2,
// Force_Field, Custom Effect), rendered inside the servo tick. THIS FILE AND
// external_effects.cpp ARE ON THE REAL-TIME PATH: no allocation, lock, log or system call;
// constant time (at most kMaxPlanes planes, one field, one buzz).
//
// Data flow: the VRPN server's I/O thread validates and clamps what clients send
// (server/vrpn_effect_commands.hpp) into one ExternalEffects value and writes it to
// commandSlot(); render() picks up the newest value at the start of a tick. Values are already
// in SI units and inside the device's limits when they arrive; render() still never produces a
// non-finite force from finite inputs, and the servo's passivity and safety stages come after it.
//
// Rendering (docs/vrpn.md §9, "what vrpn_Phantom does"):
//  - Plane i: free space where n·p + d > 0 (n unit); depth = -(n·p + d) > 0 is contact. Spring
//    k·depth plus damping -b·(v·n) along n, never pulling the pen in. Friction: a stick point on
//    the plane held by a tangential spring of the same k; it slips when the tangential force
//    exceeds mu_static·F_n and then drags at mu_dynamic·F_n. The planes' forces add up.
//  - Recovery rule (GHOST Plane::collisionDetect; stock vrpn_Phantom leaves it disabled, the
//    reference recommends it): when plane i changes while the pen is in contact with it, its
//    offset is first moved so the current depth (measured along the new normal) is kept, then
//    stepped linearly to the commanded offset over recovery_ticks ticks.
//  - Plane-0 surface effects (Plane2): a sinusoidal texture of amplitude tex_amp and wavelength
//    tex_wavelength raises the surface by tex_amp·sin(2πu/λ)·sin(2πv/λ) (u, v: plane
//    coordinates); a buzz adds k·buzz_amp·sin(2π f t) to the normal force while in contact;
//    normal adhesion pulls the pen back with k_adhesion·(height above the plane) after a contact
//    until it is lifted more than adhesion_snap_m. Lateral adhesion is accepted and not rendered.
//  - Force field: F = force + J (p - origin) while |p - origin| <= radius.
//  - Buzz effect (Custom Effect 0): amplitude·sin(2π f t)·direction for `duration` seconds from
//    the tick it arrived.
#include <Eigen/Core>
#include <array>
#include <cstdint>

#include "rt/latest_slot.hpp"

namespace thx::srv {

inline constexpr int kMaxExternalPlanes = 4;  // vrpn_Phantom's MAXPLANE

// Plain data (crosses threads by copy). SI units, world frame.
struct ExternalPlane {
  bool on = false;
  double n[3] = {0, 0, 1};  // unit
  double d_m = 0.0;
  double k_n_per_m = 0.0;
  double b_ns_per_m = 0.0;
  double mu_static = 0.0;
  double mu_dynamic = 0.0;
  std::int32_t recovery_ticks = 1;
  std::uint32_t version = 0;  // bumped by the writer on every change of this plane
};

struct ExternalSurfaceEffects {  // applied to plane 0
  double adhesion_k_n_per_m = 0.0;
  double adhesion_snap_m = 0.001;
  double texture_amplitude_m = 0.0;
  double texture_wavelength_m = 0.0;  // <= 0: no texture
  double buzz_amplitude_m = 0.0;
  double buzz_frequency_hz = 0.0;
};

struct ExternalField {
  bool on = false;
  double origin_m[3] = {};
  double force_n[3] = {};
  double jacobian_n_per_m[3][3] = {};  // [i][j] = dF_i/dx_j
  double radius_m = 0.0;
};

struct ExternalBuzz {
  bool on = false;
  double amplitude_n = 0.0;
  double frequency_hz = 0.0;
  double duration_s = 0.0;
  double direction[3] = {0, 0, 1};  // unit
  std::uint32_t version = 0;        // bumped on every new buzz: it restarts the timer
};

struct ExternalEffects {
  std::array<ExternalPlane, kMaxExternalPlanes> planes{};
  ExternalSurfaceEffects surface;
  ExternalField field;
  ExternalBuzz buzz;
};

struct ExternalOutput {
  Eigen::Vector3d force_world = Eigen::Vector3d::Zero();
  Eigen::Vector3d scp_world = Eigen::Vector3d::Zero();  // surface contact point (the tip if free)
  bool in_contact = false;                              // some plane pushes
  bool recovering = false;
};

class ExternalEffectRenderer {
 public:
  explicit ExternalEffectRenderer(double period_s);

  // The I/O thread's side (one writer).
  rt::LatestSlot<ExternalEffects>& commandSlot() { return slot_; }

  // One tick. `valid` = the device reading is good; otherwise nothing is rendered and every
  // contact history (stick points, adhesion, recovery) is forgotten.
  ExternalOutput render(const Eigen::Vector3d& p_world, const Eigen::Vector3d& v_world, bool valid);

  const ExternalEffects& current() const { return effects_; }
  bool anyActive() const;

 private:
  struct PlaneState {
    std::uint32_t version = 0;
    bool was_on = false;
    double d_eff = 0.0;  // the offset rendered now (differs from d_m during recovery)
    int steps_left = 0;
    bool in_contact = false;
    bool adhered = false;
    bool stuck_valid = false;
    Eigen::Vector3d stick = Eigen::Vector3d::Zero();
  };
  void takeCommands(const Eigen::Vector3d& p_world);
  double surfaceRaise(const Eigen::Vector3d& n, const Eigen::Vector3d& p) const;

  double period_s_;
  std::int64_t tick_ = 0;
  rt::LatestSlot<ExternalEffects> slot_;
  std::uint32_t slot_seq_ = 0;
  ExternalEffects effects_;
  std::array<PlaneState, kMaxExternalPlanes> state_{};
  std::uint32_t buzz_version_ = 0;
  std::int64_t buzz_start_tick_ = 0;
};

}  // namespace thx::srv
