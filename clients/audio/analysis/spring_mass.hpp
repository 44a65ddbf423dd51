#pragma once
// A spring-mass lattice modal model of a thin surface, the model the paper's earlier work used for
// a normal-mapped surface (Raghuvanshi & Lin 2006): one point mass per node of an nx x ny grid and
// one spring along every grid edge; each node moves along the surface normal only (1 DOF: in
// that model the three axes decouple into three copies of the same scalar problem, so one copy
// gives every frequency). K = k x (the grid's graph Laplacian), M = m I; solved by the same
// ARPACK shift-invert wrapper as the FEM (arpack_eigensolver.hpp). docs/table1.md says why it is
// here: Table 1's offline memory of the normal-map row.
#include <Eigen/Sparse>
#include <string>
#include <vector>

#include "clients/audio/analysis/elastic_material.hpp"
#include "clients/audio/analysis/modal_analysis.hpp"

namespace thx::audio {

struct SpringMassLattice {
  std::string name;              // the object (error messages)
  int nx = 2, ny = 1;            // nodes along x and y (nx >= 2, ny >= 1; ny = 1 is a chain)
  double mass_kg = 1.0;          // every node's
  double spring_n_per_m = 1.0;   // every edge's
  bool clamp_edges = false;      // hold the boundary nodes (a chain: its two ends)
};

// A surface of extent_x x extent_y and `thickness` of material m sampled by `nodes` x `nodes`:
// node mass rho t dx dy (the grid's cell area; boundary nodes alike), spring constant E t
// (Raghuvanshi & Lin 2006, Sec. 3: "spring constant = Young's modulus x thickness").
SpringMassLattice surfaceLattice(const std::string& name, double extent_x, double extent_y, double thickness,
                                 int nodes, const ElasticMaterial& m, bool clamp_edges);

struct SpringMassSystem {
  Eigen::SparseMatrix<double> stiffness, mass;  // over free nodes only
  std::vector<int> free_dof;                    // per node: its row, or -1 if held
  int free_count = 0;
};

// Throws ModalError naming lattice.name on a bad size, mass or spring constant.
SpringMassSystem assembleSpringMass(const SpringMassLattice& lattice);

// The lattice's modes: the free lattice's one rigid mode (a uniform translation) found and dropped,
// as analyse() drops a free body's six. shapes: nodes x modes, M-orthonormal, 0 at held nodes;
// mesh_dofs = free_dofs + held nodes = nodes. Throws ModalError as analyse() does.
ModalSolution springMassModes(const SpringMassLattice& lattice, const ModalSettings& settings);

}  // namespace thx::audio
