#include "clients/audio/analysis/surface_nodes.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <map>

namespace thx::audio {

SurfaceNodes surfaceNodes(const TetMesh& mesh) {
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
  SurfaceNodes out;
  out.normal.assign(mesh.nodes.size(), Eigen::Vector3d::Zero());
  out.on_surface.assign(mesh.nodes.size(), 0);
  for (const auto& [key, f] : faces) {
    if (f.count != 1) continue;
    const Eigen::Vector3d& a = mesh.nodes[std::size_t(f.corners[0])];
    Eigen::Vector3d n = (mesh.nodes[std::size_t(f.corners[1])] - a).cross(mesh.nodes[std::size_t(f.corners[2])] - a);
    if (n.dot(mesh.nodes[std::size_t(f.opposite)] - a) > 0) n = -n;  // |n| = twice the area: area weighting
    out.area += 0.5 * n.norm();
    for (int c : f.corners) out.normal[std::size_t(c)] += n, out.on_surface[std::size_t(c)] = 1;
    for (int c : f.midpoints)
      if (c >= 0) out.normal[std::size_t(c)] += n, out.on_surface[std::size_t(c)] = 1;
  }
  return out;
}

}  // namespace thx::audio
