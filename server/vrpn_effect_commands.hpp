#pragma once
// What a VRPN client's vrpn_ForceDevice messages do to the external effects (docs/vrpn.md §9): the
// PHANToM parameter clamps, unit conversion to SI, and validation. Pure functions on plain data,
// used by the VRPN server's I/O thread (never by the servo thread); unit-tested without sockets.
//
// Clamps, as vrpn_Phantom applies them (§9), then ours (marked *):
//  - Plane: kspring <= 0 -> 0.001, > 1 -> 1, times the device's maximum stiffness; fstat to
//    [0, 1]; fdyn > fstat -> 0; kdamp to [0, 0.005] N·s/mm (x1000 -> N·s/m; the unit is our
//    reading of GHOST's range); n_rec_cycles < 1 -> 1, *> 1000 -> 1000. A (0,0,0) normal turns
//    the plane off. The normal need not be unit length: (a,b,c,d) is divided by |(a,b,c)|.
//    *plane_index outside 0..3 and *non-finite values are refused (stock does not check).
//  - Plane2 (plane 0): *adhesion stiffness as a fraction of the maximum stiffness, clamped to
//    [0, 1]; *texture amplitude to [0, 2 mm] and wavelength >= 0.5 mm (else no texture);
//    *buzz amplitude to [0, 1 mm] and frequency to [0, servo rate / 2].
//  - Force_Field: all zeros (or radius <= 0) = stop. *|force| is clamped to the device's peak
//    force and J is scaled down so its Frobenius norm is at most the maximum stiffness.
//  - Custom Effect: id 0 = buzz (amplitude N, frequency Hz, duration s[, direction x,y,z]);
//    *amplitude clamped to [0, peak force], frequency to [0, servo rate / 2], duration to
//    [0, 60 s]; a zero direction means +z. 0xFFFFFFFF = stop. *Other ids are refused.
// A refused command changes nothing; its problem text names the field and value, and the server
// answers with Force_Error 0 ("value out of range") and that text. A clamped value is applied
// and reported in `note` (the server sends it as a warning text message).
#include <string>

#include "device/vrpn/force_messages.hpp"
#include "server/external_effects.hpp"

namespace thx::srv {

struct EffectLimits {
  double max_stiffness_n_per_m = 1000.0;
  double peak_force_n = 8.0;
  double servo_rate_hz = 1000.0;
  int max_recovery_ticks = 1000;
};

struct CommandVerdict {
  bool applied = false;  // the effects changed (a refused or no-op command leaves them alone)
  std::string problem;   // non-empty: refused, with the reason
  std::string note;      // non-empty: applied with a clamp worth telling the client about
};

CommandVerdict applyPlane(ExternalEffects& effects, const vrpn::ForcePlane& msg, const EffectLimits& limits);
CommandVerdict applyPlane2(ExternalEffects& effects, const vrpn::ForcePlane2& msg, const EffectLimits& limits);
CommandVerdict applyField(ExternalEffects& effects, const vrpn::ForceField& msg, const EffectLimits& limits);
CommandVerdict applyCustomEffect(ExternalEffects& effects, const vrpn::ForceCustomEffect& msg,
                                 const EffectLimits& limits);

// Everything off (the last client disconnected). Plane versions move on so the servo notices.
void resetEffects(ExternalEffects& effects);

}  // namespace thx::srv
