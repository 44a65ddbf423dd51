#pragma once
// The exact contact force of a probe against a relief grid mesh itself (srv::reliefGridMesh):
// k (q - p) with q the mesh's closest point, 0 above the mesh. bench_force_error compares the mesh
// renderer with it beside the continuous truth, which splits the mesh rows' error into what the
// mesh cannot represent and what the god object adds (its proxy keeps the side it entered from,
// not always the closest point).
#include <Eigen/Core>

#include "server/triangle_mesh.hpp"

namespace thx::bench {

class GridMeshReference {
 public:
  // `mesh` = reliefGridMesh(surface, n) over a map of `size_m`; the mesh must outlive this.
  GridMeshReference(const srv::TriangleMesh& mesh, int n, const Eigen::Vector2d& size_m);
  // z of the mesh at plane-local (x, y) inside its rectangle.
  double heightAt(double x, double y) const;
  // k (q - p), q the closest point of the mesh; zero if p is not below the mesh.
  Eigen::Vector3d force(const Eigen::Vector3d& p, double k) const;

 private:
  const Eigen::Vector3d& vertex(int r, int c) const { return mesh_->vertices[std::size_t(r) * std::size_t(n_ + 1) + std::size_t(c)]; }
  const srv::TriangleMesh* mesh_;
  int n_;
  Eigen::Vector2d size_, cell_;
};

// The point of triangle (a, b, c) closest to p.
Eigen::Vector3d closestOnTriangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                  const Eigen::Vector3d& c);

}  // namespace thx::bench
