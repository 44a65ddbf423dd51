#include "clients/physics/rest_detector.hpp"

namespace thx::phys {

bool RestDetector::update(const btTransform& pose, double radius_m, double dt_s, const RestOptions& options) {
  if (started_) {
    const double moved = double((pose.getOrigin() - reference_.getOrigin()).length());
    // A point of the bounding sphere moves by at most the centre's move plus the rotation's
    // chord 2 r sin(angle / 2) = 2 r |vector part of the turn| (precise for small angles in float).
    const btQuaternion turn = pose.getRotation() * reference_.getRotation().inverse();
    const double chord = 2.0 * radius_m * double(btVector3(turn.getX(), turn.getY(), turn.getZ()).length());
    if (moved + chord <= options.tolerance_m) {
      still_for_s_ += dt_s;
      return still_for_s_ >= options.window_s - 0.5 * dt_s;
    }
  }
  reference_ = pose;
  still_for_s_ = 0.0;
  started_ = true;
  return false;
}

}  // namespace thx::phys
