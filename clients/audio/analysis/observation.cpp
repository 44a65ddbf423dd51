#include "clients/audio/analysis/observation.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <limits>
#include <map>

#include "clients/audio/analysis/modal_error.hpp"

namespace thx::audio {

namespace {

struct Surface {
  std::vector<Pickup> pickups;
  double area = 0.0;
};

Surface surfaceOf(const TetMesh& mesh) {
  // Boundary faces: corner triangles that belong to exactly one tet, oriented away from its
  // fourth corner.
  // Tet10: a face's nodes are its corners and the midpoints of its three edges.
  struct Face {
    std::array<int, 3> corners;
    std::array<int, 3> midpoints;  // -1 for Tet4
    int opposite;
    int count;
  };
  const bool quadratic = mesh.order == ElementOrder::Quadratic;
  std::map<std::array<int, 3>, Face> faces;
  for (const auto& t : mesh.tets)
    for (int skip = 0; skip < 4; ++skip) {
      std::array<int, 3> f{}, mid{-1, -1, -1};
      int n = 0, m = 0;
      for (int c = 0; c < 4; ++c)
        if (c != skip) f[std::size_t(n++)] = t[std::size_t(c)];
      if (quadratic)
        for (std::size_t e = 0; e < kTet10Edges.size(); ++e)
          if (kTet10Edges[e][0] != skip && kTet10Edges[e][1] != skip) mid[std::size_t(m++)] = t[4 + e];
      std::array<int, 3> sorted = f;
      std::sort(sorted.begin(), sorted.end());
      auto [it, fresh] = faces.try_emplace(sorted, Face{f, mid, t[std::size_t(skip)], 0});
      ++it->second.count;
    }
  Surface out;
  std::vector<Eigen::Vector3d> normal(mesh.nodes.size(), Eigen::Vector3d::Zero());
  std::vector<char> surface(mesh.nodes.size(), 0);
  for (const auto& [key, f] : faces) {
    if (f.count != 1) continue;
    const Eigen::Vector3d& a = mesh.nodes[std::size_t(f.corners[0])];
    Eigen::Vector3d n = (mesh.nodes[std::size_t(f.corners[1])] - a).cross(mesh.nodes[std::size_t(f.corners[2])] - a);
    if (n.dot(mesh.nodes[std::size_t(f.opposite)] - a) > 0) n = -n;  // |n| = twice the area: area weighting
    out.area += 0.5 * n.norm();
    for (int c : f.corners) normal[std::size_t(c)] += n, surface[std::size_t(c)] = 1;
    for (int c : f.midpoints)
      if (c >= 0) normal[std::size_t(c)] += n, surface[std::size_t(c)] = 1;
  }
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
