#include "clients/physics/speculative_contacts.hpp"

#include <Eigen/Geometry>

namespace thx::phys {

double approachSpeed(const BodyMotion& motion, const Eigen::Vector3d& on_object, const Eigen::Vector3d& n) {
  const Eigen::Vector3d v = motion.linear + motion.angular.cross(on_object - motion.centre);
  return -v.dot(n);
}

bool keepFurtherContact(double distance, double approach_speed) {
  return distance <= 0.0 || approach_speed <= kSpeculativeApproachSpeed;
}

}  // namespace thx::phys
