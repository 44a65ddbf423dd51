#pragma once
// One sounding body: its mesh and its audible modes, and the gain of every mode for a force at
// any point of it. A force (or impulse) J at point x drives mode i by c_i(x) . J, with c_i the
// audible mode's column (audible_modes.hpp: sum over its members of u_m (w . u_m), u_m the
// M-orthonormal shape and w the body's listener, docs/audio.md §9-§9a); c_i(x) is interpolated from the nodes of the tet
// containing x with the element's own shape functions (linear for Tet4, quadratic for Tet10), so
// a point between nodes gets neither the nearest node's value nor a smeared one.
#include <Eigen/Core>
#include <array>
#include <span>
#include <vector>

#include "clients/audio/analysis/audible_modes.hpp"
#include "clients/audio/analysis/tet_mesh.hpp"

namespace thx::audio {

class ModalBody {
 public:
  // `modes.shapes` has one row per DOF of `mesh` (audibleModes of analyse(mesh, ...)); else
  // std::logic_error (a caller's mistake).
  ModalBody(TetMesh mesh, AudibleModes modes);

  const TetMesh& mesh() const { return mesh_; }
  const AudibleModes& modes() const { return modes_; }
  std::size_t size() const { return modes_.size(); }

  // gains[i] = c_i(point) . direction, in the body's (mesh's) frame. A point outside the mesh
  // (a contact point a little off a curved surface, a slab struck at the texture's edge) is
  // taken at the nearest point of the mesh. `direction` is not normalised: pass the impulse to get modal
  // impulses. gains.size() must be size().
  void gainsAt(const Eigen::Vector3d& point, const Eigen::Vector3d& direction, std::span<double> gains) const;
  std::vector<double> gainsAt(const Eigen::Vector3d& point, const Eigen::Vector3d& direction) const;

  // The containing tet and its barycentric coordinates (>= 0, summing to 1); for a point outside
  // the mesh, those of the mesh's nearest point, on its boundary faces. A scan over the tets'
  // and boundary faces' bounding boxes: a contact report locates two points, every report, and
  // the brute force over every tet's four faces was most of a ball-on-block render's CPU (perf).
  struct Location {
    int tet = 0;
    Eigen::Vector4d barycentric{1.0, 0.0, 0.0, 0.0};
    bool inside = true;  // false: the point lay outside every tet
  };
  Location locate(const Eigen::Vector3d& point) const;

  // The nodes a point's shape functions weigh and their weights (4 for Tet4, 10 for Tet10):
  // gainsAt is the sum over them of weight x (node's shape . direction). The live client sends
  // them with a Point event and the callback sums the same way (synth_scene.hpp).
  struct Weights {
    int nodes[10] = {};
    double weights[10] = {};
    int count = 0;
  };
  Weights weightsAt(const Eigen::Vector3d& point) const;

 private:
  TetMesh mesh_;
  AudibleModes modes_;
  std::vector<Eigen::Matrix3d> inverse_;  // per tet: barycentric (1..3) = inverse * (x - corner 0)
  struct Box {
    Eigen::Vector3d lo, hi;
  };
  struct Face {
    int tet;
    std::array<int, 3> corners;
    Box box;
  };
  std::vector<Box> tet_boxes_;  // per tet, padded by a hair for the barycentric tolerance
  std::vector<Face> boundary_;  // faces of exactly one tet, in tet order
};

}  // namespace thx::audio
