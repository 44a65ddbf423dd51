#pragma once
// K x = lambda M x for the eigenvalues nearest a negative shift sigma (so the lowest ones), with
// ARPACK's symmetric driver (dsaupd/dseupd) in shift-invert mode 3: OP = (K - sigma M)^-1 M, the
// M inner product, and K - sigma M (SPD for sigma < 0) factored once: by CHOLMOD's supernodal
// Cholesky (SuiteSparse, dense BLAS blocks; the default) or Eigen's SimplicialLDLT (AMD ordering).
// Eigenvectors come out M-orthonormal.
#include <Eigen/Core>
#include <Eigen/Sparse>
#include <functional>
#include <string>

namespace thx::audio {

// How K - sigma M is factored. Both are exact sparse factorizations with a fill-reducing ordering
// (AMD, or METIS when CHOLMOD finds it better); the supernodal one does its work in dense blocks,
// several times faster on the Tet10 meshes here (docs/audio.md §8.5).
enum class Factorization { CholmodSupernodal, SimplicialLdlt };

struct EigenSolveSettings {
  Factorization factorization = Factorization::CholmodSupernodal;
  int eigenpairs = 36;        // nev
  int lanczos_vectors = 0;    // ncv; 0 = max(2 nev + 1, nev + 40), at most the dimension
  double shift = -1.6e4;      // sigma, rad^2/s^2; must be < 0
  double tolerance = 1e-10;   // ARPACK's relative Ritz value tolerance
  int max_iterations = 1000;  // implicit restarts
};

struct EigenSolveStats {
  double factor_s = 0.0, iterate_s = 0.0;          // wall clock
  double factor_cpu_s = 0.0, iterate_cpu_s = 0.0;  // the process's CPU time (every thread)
  int operator_applications = 0;
  int restarts = 0;
};

// `progress(applications)` is called after every 25th application of OP (long solves).
struct EigenSolveResult {
  Eigen::VectorXd values;   // ascending, rad^2/s^2
  Eigen::MatrixXd vectors;  // dimension x pairs, M-orthonormal
  EigenSolveStats stats;
};

// The process's CPU time so far, s (on a machine shared with other work, a steadier measure of a
// solve's cost than the wall clock).
double processCpuSeconds();

// Throws ModalError naming `object` if the factorization fails, ARPACK reports an error, or
// fewer than the requested pairs converge.
EigenSolveResult solveLowestModes(const std::string& object, const Eigen::SparseMatrix<double>& stiffness,
                                  const Eigen::SparseMatrix<double>& mass, const EigenSolveSettings& settings,
                                  const std::function<void(int)>& progress = {});

}  // namespace thx::audio
