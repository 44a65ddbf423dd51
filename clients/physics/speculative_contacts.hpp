#pragma once
// Which of a ball's further relief contacts Bullet may take before they touch.
//
// Bullet's solver treats a point with a positive gap as speculative: it lets the body approach
// the point by at most that gap within the step, extrapolating its straight motion. On a relief
// a ball rolling across a trough touches the near flank (its deepest point) while the far flank's
// point, still open, is ahead of it. The near flank turns the ball's path within the step, but
// the speculative far point does not know that: it takes the ball's impact early and too hard.
// The relief plane then lost 0.16 and 0.20 more of a ball's speed over 60 ridges than the
// rolling-impact law (slopes 0.05 and 0.1, 1 ms steps; docs/physics.md, "A ball on a relief").
//
// Rule: a further point (not the deepest) whose gap is positive is left out while the ball moves
// onto it faster than kSpeculativeApproachSpeed (its velocity at the point, along the point's
// normal). The deepest point always stays, and so does every point of a ball at rest or
// creeping: resting on a groove's two walls it needs both, gap or none (a gap threshold instead
// of the speed lost that rest at 60 Hz). A point left out is met next step, once it touches.
#include <Eigen/Core>

namespace thx::phys {

// Approach speeds above this (m/s) are an impact still to come, not a rest to hold.
inline constexpr double kSpeculativeApproachSpeed = 0.01;

// A rigid body's motion in the world frame.
struct BodyMotion {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();   // of mass
  Eigen::Vector3d linear = Eigen::Vector3d::Zero();   // velocity of the centre
  Eigen::Vector3d angular = Eigen::Vector3d::Zero();  // rad/s
};

// How fast the body's point `on_object` moves onto a surface whose normal there is `n` (unit,
// pointing from the surface to the body): > 0 approaching.
double approachSpeed(const BodyMotion& motion, const Eigen::Vector3d& on_object, const Eigen::Vector3d& n);

// Whether a further contact (not the deepest) with signed gap `distance` stays in the manifold.
bool keepFurtherContact(double distance, double approach_speed);

// The widest gap a further contact kept by keepFurtherContact can close within a step of `step_s`
// (0: not known, nothing open closes), twice over for the point's refinement within its texel
// (a few µm). A point open wider takes no impulse in that step: it costs the solver and does
// nothing.
inline double closableGap(double step_s) { return 2.0 * kSpeculativeApproachSpeed * step_s; }

}  // namespace thx::phys
