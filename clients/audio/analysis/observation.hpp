#pragma once
// The listener of a body (docs/audio.md §9a): a fixed linear functional w of its displacement
// field, the mean outward normal displacement at four pickup points on its surface times the
// body's surface area (m^3: a larger surface radiates more for the same motion; a size weighting
// between bodies, not a radiation model). A mode u_i
// struck by a modal impulse J . u_i(x) sounds with (J . u_i(x)) (w . u_i); summed over any
// M-orthonormal basis U of a degenerate subspace that is J^T U U^T w, the same for every basis
// the eigensolver may return, and a mode's sign cancels. Without w (the sum of the modal
// coordinates) the sound depended on that basis.
//
// The pickups: for each fixed target a_k (below, in the mesh's bounding box scaled to [-1, 1]^3),
// the surface node (a corner or, for Tet10, an edge midpoint of a boundary face) not held at
// zero nearest to it. The targets sit at generic points of different
// faces (top, bottom and two sides), so no pickup lies on a symmetry plane of the box-, slab-,
// sphere- or cylinder-shaped meshes and no mode family is silenced by symmetry, unlike a surface
// integral (a pure monopole hears almost nothing of a free body's modes).
#include <Eigen/Core>
#include <array>
#include <vector>

#include "clients/audio/analysis/tet_mesh.hpp"

namespace thx::audio {

inline constexpr std::array<std::array<double, 3>, 4> kPickupTargets{{
    {0.53, 0.29, 1.0}, {-0.37, 0.61, -1.0}, {1.0, -0.43, 0.17}, {-0.19, -1.0, -0.71}}};

struct Pickup {
  int node = 0;
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  // outward, unit: area-weighted over its boundary faces
};

// The pickup nearest to each of kPickupTargets. Throws ModalError naming the mesh when it has no
// surface node free to move.
std::vector<Pickup> pickups(const TetMesh& mesh);

// The area of the mesh's boundary faces (their corner triangles), m^2.
double surfaceArea(const TetMesh& mesh);

// w as a vector over the mesh DOFs (3 x node + axis): w . u is surfaceArea times the mean of
// normal . u(node) over the pickups, in m^3 for u in metres.
Eigen::VectorXd observationVector(const TetMesh& mesh);

}  // namespace thx::audio
