#include "clients/audio/synthesis/relief_impulses.hpp"

#include <algorithm>

namespace thx::audio {
namespace {

// -(v_t . n) / (n_g . n): the speed along n_g at which a contact sliding at v_t follows a
// surface of normal n.
double normalSpeed(const Eigen::Vector3d& ng, const Eigen::Vector3d& n, const Eigen::Vector3d& vt, double floor) {
  return -vt.dot(n) / std::max(ng.dot(n), floor);
}

}  // namespace

double reliefImpulse(const ReliefTick& before, const ReliefTick& now, double mass_kg, double min_normal_dot) {
  if (!before.in_contact || !now.in_contact) return 0.0;
  const Eigen::Vector3d& ng = now.geometric_normal;
  const Eigen::Vector3d vt = now.velocity - now.velocity.dot(ng) * ng;
  return mass_kg * (normalSpeed(ng, now.contact_normal, vt, min_normal_dot) -
                    normalSpeed(ng, before.contact_normal, vt, min_normal_dot));
}

}  // namespace thx::audio
