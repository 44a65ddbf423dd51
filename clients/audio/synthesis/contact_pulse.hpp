#pragma once
// The finite duration of an impact (Hertz contact) and what it does to each mode.
//
// Two elastic bodies pressed together at closing speed v behave as a nonlinear spring
// (Hertz: F = 4/3 E* sqrt(R*) delta^(3/2)); the contact lasts
//   tau = 2.868 (m*^2 / (R* E*^2 v))^(1/5)                       (Johnson, Contact Mechanics, §11.4)
// with 1/E* = (1 - nu_a^2)/E_a + (1 - nu_b^2)/E_b, 1/R* = 1/R_a + 1/R_b and 1/m* = 1/m_a + 1/m_b
// (a flat face has 1/R = 0, the ground or a kinematic body 1/m = 0, a rigid one 1/E = 0).
// So tau ~ v^(-1/5) and ~ E*^(-2/5): harder materials ring brighter.
//
// The force is modelled as a half-sine pulse of that duration carrying the impulse J,
//   F(t) = (pi J / (2 tau)) sin(pi t / tau),  0 <= t <= tau.
// An undamped mode of angular frequency w driven by it rings after the pulse exactly as if
// struck by the impulse J * P(w tau) at the pulse's centre t = tau/2, with
//   P(x) = pi^2 cos(x/2) / (pi^2 - x^2)   (P(0) = 1, P(pi) = pi/4, zeros at 3pi, 5pi, ...):
// the pulse's spectrum, a low-pass that leaves slow modes the full impulse and starves modes
// whose period is shorter than the contact.
#include <limits>

namespace thx::audio {

struct HertzSide {
  double youngs_pa = std::numeric_limits<double>::infinity();  // infinity: rigid
  double poisson = 0.0;
  double radius_m = std::numeric_limits<double>::infinity();   // curvature radius at the contact; infinity: flat
  double mass_kg = std::numeric_limits<double>::infinity();    // infinity: fixed or kinematic
};

// tau in seconds. Throws thx::Error (Config) unless approach_speed > 0, some side has a finite
// radius, a finite modulus and a finite mass (otherwise there is no Hertz contact: the caller
// strikes an ideal impulse instead).
double hertzContactDuration(const HertzSide& a, const HertzSide& b, double approach_speed_m_per_s);

// P(omega * tau) above (signed: beyond x = 3 pi the mode rings in opposite phase).
double halfSinePulseFactor(double omega_rad_per_s, double duration_s);

}  // namespace thx::audio
