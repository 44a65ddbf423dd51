#include "clients/audio/analysis/observation.hpp"

#include <algorithm>
#include <limits>

#include "clients/audio/analysis/modal_error.hpp"
#include "clients/audio/analysis/surface_nodes.hpp"

namespace thx::audio {

namespace {

struct Surface {
  std::vector<Pickup> pickups;
  double area = 0.0;
};

Surface surfaceOf(const TetMesh& mesh) {
  const SurfaceNodes nodes = surfaceNodes(mesh);
  const std::vector<Eigen::Vector3d>& normal = nodes.normal;
  const std::vector<char>& surface = nodes.on_surface;
  Surface out;
  out.area = nodes.area;
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const Eigen::Vector3d& x : mesh.nodes) lo = lo.cwiseMin(x), hi = hi.cwiseMax(x);
  const Eigen::Vector3d centre = 0.5 * (lo + hi);
  Eigen::Vector3d half = 0.5 * (hi - lo);
  half = half.cwiseMax(1e-12 * half.maxCoeff());

  for (const auto& a : kPickupTargets) {
    const Eigen::Vector3d target(a[0], a[1], a[2]);
    int best = -1;
    double best_d = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < mesh.nodes.size(); ++i) {
      const bool held = i < mesh.clamped.size() && mesh.clamped[i];
      if (!surface[i] || held || normal[i].squaredNorm() == 0.0) continue;
      const double d = ((mesh.nodes[i] - centre).cwiseQuotient(half) - target).squaredNorm();
      if (d < best_d) best_d = d, best = int(i);  // ties: the lowest node index
    }
    if (best < 0) throw ModalError(mesh.name + ": no surface node free to move, nowhere to listen (observation.hpp)");
    out.pickups.push_back({best, normal[std::size_t(best)].normalized()});
  }
  return out;
}

}  // namespace

std::vector<Pickup> pickups(const TetMesh& mesh) { return surfaceOf(mesh).pickups; }

double surfaceArea(const TetMesh& mesh) { return surfaceOf(mesh).area; }

Eigen::VectorXd observationVector(const TetMesh& mesh) {
  Eigen::VectorXd w = Eigen::VectorXd::Zero(mesh.dofCount());
  const Surface s = surfaceOf(mesh);
  for (const Pickup& p : s.pickups)
    w.segment<3>(3 * Eigen::Index(p.node)) += s.area / double(s.pickups.size()) * p.normal;
  return w;
}

}  // namespace thx::audio
