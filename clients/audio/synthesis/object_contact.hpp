#pragma once
// A lasting contact between two objects (a ball rolling or sliding on a block or on another ball)
// at the micro level (docs/audio.md §10a): neither has a texture, so the excitation is the
// fractal roughness (fractal_roughness.hpp) read along the distance the contact travels, its pitch
// following the relative tangential speed, its loudness the normal force. This file holds the
// choice of that speed and of the loudness of rolling against sliding; PhysicsExcitation routes
// the resulting force segments to both bodies.
namespace thx::audio {

struct ObjectContactOptions {
  bool enabled = true;
  // The roughness force of pure rolling relative to sliding at the same speed (our choice: rolling
  // noise is quieter than sliding, about -12 dB here; not a measured value).
  double rolling_share = 0.25;
  // Below this travel speed the contact is at rest: no force at all (exact silence), so the
  // physics engine's settling makes no sound (a ball set down on a block moved at up to 2 mm/s
  // for its first 15 ms in Bullet; docs/audio.md §10a).
  double min_speed_m_per_s = 5e-3;
};

// How fast the profile is read and how loud: from the slip speed |v_slip| (a's contact point
// relative to b's, tangential) and the travel speed (a's centre relative to b's material at the
// contact, tangential: how fast the contact moves over b, what the surface path's texel path
// follows). speed = max(slip, travel); weight = (slip + rolling_share (speed - slip)) / speed:
// 1 for pure sliding, rolling_share for pure rolling. Both 0 below min_speed_m_per_s.
struct ContactTravel {
  double speed_m_per_s = 0.0;
  double weight = 0.0;
};
ContactTravel contactTravel(double slip_m_per_s, double travel_m_per_s, const ObjectContactOptions& options);

}  // namespace thx::audio
