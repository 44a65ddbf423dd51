#include "clients/audio/synthesis/meso_impulses.hpp"

#include <algorithm>

namespace thx::audio {

Eigen::Vector3d mesoMomentum(const MesoSurface& s, const Eigen::Vector3f& sampled_normal, const Eigen::Vector3d& velocity) {
  const Eigen::Vector3d& ng = s.geometric_normal;
  const Eigen::Vector3d ns = sampled_normal.cast<double>();
  const Eigen::Vector3d vt = velocity - velocity.dot(ng) * ng;
  const double denominator = std::max(ng.dot(ns), s.min_normal_dot);
  return s.mass_kg * (-vt.dot(ns) / denominator) * ng;
}

std::vector<MesoImpulse> mesoImpulses(const MesoSurface& surface, std::span<const PathPoint> path) {
  std::vector<MesoImpulse> out;
  MesoState state;
  for (std::size_t k = 1; k < path.size(); ++k)
    mesoImpulsesAlong(surface, state, path[k - 1].uv, path[k].uv, path[k].velocity,
                      [&](const MesoImpulse& m) { out.push_back(m); });
  return out;
}

}  // namespace thx::audio
