#pragma once
// Global stiffness K and consistent mass M of a tet mesh, over its free DOFs only (clamped nodes'
// DOFs are removed). Both are symmetric; full (both triangles) column-major sparse matrices.
#include <Eigen/Sparse>
#include <vector>

#include "clients/audio/analysis/elastic_material.hpp"
#include "clients/audio/analysis/tet_mesh.hpp"

namespace thx::audio {

struct AssembledSystem {
  Eigen::SparseMatrix<double> stiffness;  // N/m
  Eigen::SparseMatrix<double> mass;       // kg
  std::vector<int> free_dof;              // per mesh DOF (3 * node + axis): its row, or -1 if clamped
  int free_count = 0;
  double volume_m3 = 0.0;
};

// Throws ModalError (object named) on a bad material or a degenerate element.
AssembledSystem assemble(const TetMesh& mesh, const ElasticMaterial& material);

}  // namespace thx::audio
