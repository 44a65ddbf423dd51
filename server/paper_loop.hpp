#pragma once
// The source paper's own haptic loop as a named mode (issue 12; docs/stability.md): the graphics
// side computes one plane per frame (about 100 Hz, the paper's §4.3), a single plane through the
// surface point under the tip with the sampled normal (Eq. 3), and the device renders that plane
// at the servo rate until the next frame. No recovery rule, no crease handling, no passivity
// controller. The safety stage stays: it protects the device, not the rendering.
//
// Configuration time only.
#include "server/servo_rig.hpp"

namespace thx::srv {

constexpr double kPaperPlaneRateHz = 100.0;

// Ticks one plane is held: servo_hz / plane_rate_hz rounded, at least 1. Throws thx::Error naming
// the value unless 0 < plane_rate_hz <= servo_hz.
int planeHoldTicks(double servo_hz, double plane_rate_hz);

// Turns `wiring` (its renderer's stiffness and damping kept) into the paper's loop.
void applyPaperLoop(ServoRigConfig& wiring, double plane_rate_hz);

}  // namespace thx::srv
