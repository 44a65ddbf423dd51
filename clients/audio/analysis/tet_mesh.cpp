#include "clients/audio/analysis/tet_mesh.hpp"

#include <algorithm>
#include <Eigen/Dense>
#include <cmath>
#include <functional>

#include "clients/audio/analysis/modal_error.hpp"

namespace thx::audio {

bool TetMesh::anyClamped() const { return std::any_of(clamped.begin(), clamped.end(), [](char c) { return c != 0; }); }

namespace {

using Map = std::function<Eigen::Vector3d(const Eigen::Vector3d&)>;  // parameter in [0,1]^3 -> metres

double signedVolume(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                    const Eigen::Vector3d& d) {
  return (b - a).dot((c - a).cross(d - a)) / 6.0;
}

// The structured grid: (n+1)^3 points per linear grid; quadratic elements live on the grid of
// twice the resolution, corners on even points.
TetMesh structuredMesh(const std::string& name, GridCells cells, ElementOrder order, const Map& map) {
  if (cells.x < 1 || cells.y < 1 || cells.z < 1)
    throw ModalError(name + ": mesh cells " + std::to_string(cells.x) + "x" + std::to_string(cells.y) + "x" +
                     std::to_string(cells.z) + ": expected at least 1 along each axis");
  const int r = order == ElementOrder::Linear ? 1 : 2;  // grid points per cell edge
  const int px = r * cells.x + 1, py = r * cells.y + 1, pz = r * cells.z + 1;
  TetMesh mesh;
  mesh.name = name;
  mesh.order = order;
  mesh.nodes.reserve(std::size_t(px) * py * pz);
  for (int k = 0; k < pz; ++k)
    for (int j = 0; j < py; ++j)
      for (int i = 0; i < px; ++i)
        mesh.nodes.push_back(map(Eigen::Vector3d(double(i) / (px - 1), double(j) / (py - 1), double(k) / (pz - 1))));
  mesh.clamped.assign(mesh.nodes.size(), 0);
  auto id = [&](const Eigen::Vector3i& g) { return g.x() + px * (g.y() + py * g.z()); };

  // The 6 Kuhn tetrahedra: 000 -> e_a -> e_a + e_b -> 111 for each permutation (a, b, c).
  constexpr std::array<std::array<int, 3>, 6> kPermutations{{{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}}};
  for (int cz = 0; cz < cells.z; ++cz)
    for (int cy = 0; cy < cells.y; ++cy)
      for (int cx = 0; cx < cells.x; ++cx) {
        // Cells in the lower half of an axis are mirrored along it, so every cell's Kuhn diagonal
        // points away from the centre: no tet then has all four corners on the boundary (a
        // sphere's corner cells would flatten them) and the mesh keeps the shape's mirror symmetry.
        const Eigen::Vector3i cell(cx, cy, cz), count(cells.x, cells.y, cells.z);
        Eigen::Vector3i origin, dir;
        for (int a = 0; a < 3; ++a) {
          const bool mirrored = 2 * cell[a] + 1 < count[a];
          dir[a] = mirrored ? -1 : 1;
          origin[a] = r * (cell[a] + (mirrored ? 1 : 0));
        }
        for (const auto& p : kPermutations) {
          std::array<Eigen::Vector3i, 4> corner;
          corner[0] = origin;
          corner[1] = corner[0] + r * dir[p[0]] * Eigen::Vector3i::Unit(p[0]);
          corner[2] = corner[1] + r * dir[p[1]] * Eigen::Vector3i::Unit(p[1]);
          corner[3] = origin + r * dir;
          if (signedVolume(mesh.nodes[id(corner[0])], mesh.nodes[id(corner[1])], mesh.nodes[id(corner[2])],
                           mesh.nodes[id(corner[3])]) < 0)
            std::swap(corner[1], corner[2]);
          std::array<int, 10> tet{};
          for (int a = 0; a < 4; ++a) tet[a] = id(corner[a]);
          if (order == ElementOrder::Quadratic)
            for (int e = 0; e < 6; ++e) tet[4 + e] = id((corner[kTet10Edges[e][0]] + corner[kTet10Edges[e][1]]) / 2);
          mesh.tets.push_back(tet);
        }
      }
  return mesh;
}

// Maps [-1,1]^n radially so that the shell max|q| = s becomes the sphere |x| = s.
Eigen::Vector3d cubeToBall(const Eigen::Vector3d& q, int dims) {
  const Eigen::Vector3d head = dims == 3 ? q : Eigen::Vector3d(q.x(), q.y(), 0.0);
  const double n2 = head.norm();
  if (n2 == 0.0) return q;
  const double ninf = head.cwiseAbs().maxCoeff();
  Eigen::Vector3d out = q;
  out.head(dims) = head.head(dims) * (ninf / n2);
  return out;
}

void checkPositive(const std::string& name, const char* what, double v) {
  if (!(std::isfinite(v) && v > 0))
    throw ModalError(name + ": " + what + " " + std::to_string(v) + " m: expected a finite length > 0");
}

}  // namespace

TetMesh boxMesh(const std::string& name, const Eigen::Vector3d& size, GridCells cells, ElementOrder order) {
  for (int a = 0; a < 3; ++a) checkPositive(name, "box size", size[a]);
  return structuredMesh(name, cells, order,
                        [&](const Eigen::Vector3d& p) { return Eigen::Vector3d((p.array() - 0.5) * size.array()); });
}

TetMesh slabMesh(const std::string& name, double extent_x, double extent_y, double thickness, GridCells cells,
                 ElementOrder order, bool clamp_edges) {
  checkPositive(name, "slab extent_x", extent_x);
  checkPositive(name, "slab extent_y", extent_y);
  checkPositive(name, "slab thickness", thickness);
  TetMesh mesh = structuredMesh(name, cells, order, [&](const Eigen::Vector3d& p) {
    return Eigen::Vector3d((p.x() - 0.5) * extent_x, (p.y() - 0.5) * extent_y, (p.z() - 1.0) * thickness);
  });
  if (clamp_edges) {
    const double tol = 1e-9 * std::max(extent_x, extent_y);
    for (std::size_t n = 0; n < mesh.nodes.size(); ++n) {
      const Eigen::Vector3d& x = mesh.nodes[n];
      if (std::fabs(std::fabs(x.x()) - 0.5 * extent_x) < tol || std::fabs(std::fabs(x.y()) - 0.5 * extent_y) < tol)
        mesh.clamped[n] = 1;
    }
  }
  return mesh;
}

TetMesh sphereMesh(const std::string& name, double radius, int cells, ElementOrder order) {
  checkPositive(name, "sphere radius", radius);
  return structuredMesh(name, {cells, cells, cells}, order,
                        [&](const Eigen::Vector3d& p) { return Eigen::Vector3d(radius * cubeToBall(2.0 * p.array() - 1.0, 3)); });
}

TetMesh cylinderMesh(const std::string& name, double radius, double length, int cells, int cells_z,
                     ElementOrder order) {
  checkPositive(name, "cylinder radius", radius);
  checkPositive(name, "cylinder length", length);
  return structuredMesh(name, {cells, cells, cells_z}, order, [&](const Eigen::Vector3d& p) {
    const Eigen::Vector3d q(2.0 * p.x() - 1.0, 2.0 * p.y() - 1.0, 0.0);
    const Eigen::Vector3d d = radius * cubeToBall(q, 2);
    return Eigen::Vector3d(d.x(), d.y(), (p.z() - 0.5) * length);
  });
}

TetMesh scaled(TetMesh mesh, double s) {
  for (Eigen::Vector3d& x : mesh.nodes) x *= s;
  return mesh;
}

}  // namespace thx::audio
