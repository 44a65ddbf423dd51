#include "device/sim_planes.hpp"

#include <algorithm>
#include <cmath>

namespace thx::dev {

Eigen::Vector3d planeForce(const DeviceCommand& command, const SimBodyState& s) {
  Eigen::Vector3d f = Eigen::Vector3d::Zero();
  const int count = std::clamp(command.num_planes, 0, kMaxPlanes);
  for (int i = 0; i < count; ++i) {
    const PlaneProxy& p = command.planes[std::size_t(i)];
    const double n_norm = p.n_world.norm();
    if (!std::isfinite(n_norm) || n_norm < 1e-9 || !std::isfinite(p.d_m) || !std::isfinite(p.k_n_per_m) ||
        !std::isfinite(p.b_ns_per_m))
      continue;
    const Eigen::Vector3d n = p.n_world / n_norm;
    const double depth_m = p.d_m - n.dot(s.x_m);
    if (depth_m <= 0.0) continue;
    const double push_n = p.k_n_per_m * depth_m - p.b_ns_per_m * n.dot(s.v_m_per_s);
    if (push_n > 0.0) f += push_n * n;
  }
  return f;
}

}  // namespace thx::dev
