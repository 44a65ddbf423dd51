#pragma once
// When a body is at rest: it has stayed within a small distance of one pose for a while.
//
// A body touching its support at several points can settle into a limit cycle of the contact
// solve instead of standing still: measured, a ball on a groove's two walls rattled ±1.9 µm at
// 60 Hz (0.23 mm/s), a ball in a dimple of its own radius at 2-4 mm/s, a box on a normal map at
// 60 Hz at 0.09 mm/s, and an audio client turns any of that into a buzz (docs/physics.md, "Rest").
// Its instantaneous speed says nothing then; its displacement over a window does: a body whose
// centre, and every point of its bounding sphere under its rotation, stay within `tolerance_m`
// of where they were for `window_s` is at rest. Steady motion slower than tolerance / window
// (40 µm/s by default) counts as rest too: that is the speed below which a body is still.
//
// TexturedWorld uses it in place of Bullet's own sleeping criterion (instantaneous speeds under
// thresholds for 2 s); what happens at rest is Bullet's: the island of bodies all at rest goes
// to sleep, its velocities are zeroed, and a touch by an active or kinematic body wakes it.
#include <BulletDynamics/Dynamics/btRigidBody.h>

namespace thx::phys {

struct RestOptions {
  bool enabled = true;
  double tolerance_m = 10e-6;  // above the limit cycles' ±2 µm, far below a texel
  double window_s = 0.25;
};

class RestDetector {
 public:
  // One step of dt_s for `body`, after integration: true when the body has been at rest for the
  // whole window. `radius_m`: the body's bounding-sphere radius (rotation moves its surface).
  bool update(const btTransform& pose, double radius_m, double dt_s, const RestOptions& options);
  // Starts a new window at the current pose (a body woken by a touch must prove rest anew).
  void restart() { started_ = false; }

 private:
  btTransform reference_;
  double still_for_s_ = 0.0;
  bool started_ = false;
};

}  // namespace thx::phys
