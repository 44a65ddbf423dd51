#pragma once
// Tetrahedral meshes for modal analysis: linear (Tet4) or quadratic (Tet10) elements, and the
// structured meshes of the shapes the scenes use (box, surface slab, sphere, cylinder).
//
// Tet10 node order: corners 0-3, then the edge midpoints (0,1) (1,2) (0,2) (0,3) (1,3) (2,3).
// Structured meshes split every cell of a grid into the 6 Kuhn tetrahedra along a main diagonal
// (conforming across cells; the diagonal points away from the grid's centre). Quadratic meshes use the grid at twice the resolution, so
// every edge midpoint is a grid point; curved shapes map every node, midpoints included, so their
// quadratic elements follow the curved surface (isoparametric).
#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

namespace thx::audio {

enum class ElementOrder { Linear = 1, Quadratic = 2 };  // Tet4, Tet10

struct TetMesh {
  std::string name;  // the object it belongs to (error messages)
  ElementOrder order = ElementOrder::Linear;
  std::vector<Eigen::Vector3d> nodes;      // metres
  std::vector<std::array<int, 10>> tets;   // 4 or 10 node indices used, as `order` says
  std::vector<char> clamped;               // per node: 1 = displacement held at zero

  int nodesPerTet() const { return order == ElementOrder::Linear ? 4 : 10; }
  int dofCount() const { return 3 * int(nodes.size()); }
  bool anyClamped() const;
};

inline constexpr std::array<std::array<int, 2>, 6> kTet10Edges{{{0, 1}, {1, 2}, {0, 2}, {0, 3}, {1, 3}, {2, 3}}};

// Grid cells along each axis; each must be >= 1.
struct GridCells {
  int x = 1, y = 1, z = 1;
};

// A box of full edge lengths `size`, centred on the origin.
TetMesh boxMesh(const std::string& name, const Eigen::Vector3d& size, GridCells cells, ElementOrder order);
// The surface slab: a box of extent_x x extent_y x thickness, its top face at z = 0; with
// `clamp_edges` every node on the four side faces is held.
TetMesh slabMesh(const std::string& name, double extent_x, double extent_y, double thickness, GridCells cells,
                 ElementOrder order, bool clamp_edges);
// A ball of radius r: a cube of `cells` per side mapped radially (cube shells onto spheres).
TetMesh sphereMesh(const std::string& name, double radius, int cells, ElementOrder order);
// A solid cylinder along z of radius r and full length l, centred on the origin: a square
// cross-section of `cells` per side mapped radially onto the disc, `cells_z` along the axis.
TetMesh cylinderMesh(const std::string& name, double radius, double length, int cells, int cells_z,
                     ElementOrder order);

// The same mesh with every coordinate multiplied by s.
TetMesh scaled(TetMesh mesh, double s);

}  // namespace thx::audio
