#pragma once
// Modal analysis of one object: mesh + material -> its elastic modes (the rigid-body modes of a
// free body found and dropped), through the cache when one is given (docs/audio.md §2).
#include <Eigen/Core>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "clients/audio/analysis/arpack_eigensolver.hpp"
#include "clients/audio/analysis/elastic_material.hpp"
#include "clients/audio/analysis/tet_mesh.hpp"

namespace thx::audio {

struct ModalSettings {
  int elastic_modes = 30;        // elastic modes to compute (the 6 rigid ones of a free body come on top)
  double shift_hz = 20.0;        // sigma = -(2 pi shift_hz)^2
  double tolerance = 1e-10;      // ARPACK's relative Ritz value tolerance
  int max_iterations = 1000;     // ARPACK implicit restarts
  int lanczos_vectors = 0;       // 0 = ARPACK default chosen in arpack_eigensolver.hpp
  double rigid_below_hz = 1.0;   // a mode below this is a rigid-body mode
  Factorization factorization = Factorization::CholmodSupernodal;  // of K - sigma M
};

struct ModalSolution {
  int mesh_dofs = 0;                 // 3 x nodes
  int free_dofs = 0;                 // the eigenproblem's dimension
  int rigid_modes = 0;               // found and dropped (6 for a free body, 0 when clamped)
  Eigen::VectorXd rigid_hz;          // their frequencies (sqrt of |lambda|, signed by lambda)
  Eigen::VectorXd omega_rad_per_s;   // elastic, ascending
  Eigen::MatrixXd shapes;            // mesh_dofs x modes, M-orthonormal, 0 at clamped DOFs
  // w . u_i of each elastic mode, w the mesh's listener (observation.hpp). Filled by analyse()
  // from the mesh, also for a solution read from the cache (which stores only the shapes), so
  // another choice of w never needs a new cache file. audibleModes() requires it.
  Eigen::VectorXd observation;
  // How it was obtained.
  bool from_cache = false;
  std::string cache_file;
  double assemble_s = 0.0, factor_s = 0.0, iterate_s = 0.0, total_s = 0.0;  // wall clock
  double assemble_cpu_s = 0.0, factor_cpu_s = 0.0, iterate_cpu_s = 0.0;    // CPU time (every thread)
  int operator_applications = 0;

  double frequencyHz(int mode) const;
};

struct AnalysisOptions {
  std::optional<std::string> cache_dir;            // none = no cache
  std::function<void(const std::string&)> progress;  // one line per stage / long-solve step
};

// Throws ModalError naming mesh.name and the cause: bad material, degenerate tet, failed or
// unconverged solve, or a rigid-mode count other than 6 (free) or 0 (clamped), or no surface node
// free to move (nowhere to listen).
ModalSolution analyse(const TetMesh& mesh, const ElasticMaterial& material, const ModalSettings& settings,
                      const AnalysisOptions& options = {});

// Shared by analyse() and the spring-mass lattice (spring_mass.hpp), which solve K x = lambda M x
// the same way with different systems:
// A mode's frequency in Hz from its eigenvalue, negative for a negative eigenvalue.
double signedHz(double lambda);
// The solver's settings for `settings`, with `rigid` more eigenpairs for the rigid modes.
EigenSolveSettings eigenSolveSettings(const ModalSettings& settings, int rigid);
// The eigenpairs below settings.rigid_below_hz (the first ones; r's values ascend).
int rigidModeCount(const EigenSolveResult& r, const ModalSettings& settings);
// Fills s's solver statistics, rigid_modes and rigid_hz (r's first `rigid` pairs) and its elastic
// modes: omega and the shapes over s.mesh_dofs rows, each mesh DOF i taken from r's row free_dof[i]
// (0 where free_dof[i] < 0).
void takeModes(const EigenSolveResult& r, int rigid, const std::vector<int>& free_dof, ModalSolution& s);

// The rows of a full mesh-DOF vector block that belong to free DOFs (free_dof from assemble()).
Eigen::MatrixXd freeRows(const Eigen::MatrixXd& full, const std::vector<int>& free_dof, int free_count);

}  // namespace thx::audio
