#pragma once
// K x = lambda M x for the eigenvalues nearest a negative shift sigma (so the lowest ones), with
// ARPACK's symmetric driver (dsaupd/dseupd) in shift-invert mode 3: OP = (K - sigma M)^-1 M, the
// M inner product, and K - sigma M (SPD for sigma < 0) factored once by Eigen's SimplicialLDLT.
// Eigenvectors come out M-orthonormal.
#include <Eigen/Core>
#include <Eigen/Sparse>
#include <functional>
#include <string>

namespace thx::audio {

struct EigenSolveSettings {
  int eigenpairs = 36;        // nev
  int lanczos_vectors = 0;    // ncv; 0 = max(2 nev + 1, nev + 20), at most the dimension
  double shift = -1.6e4;      // sigma, rad^2/s^2; must be < 0
  double tolerance = 1e-10;   // ARPACK's relative Ritz value tolerance
  int max_iterations = 1000;  // implicit restarts
};

struct EigenSolveStats {
  double factor_s = 0.0, iterate_s = 0.0;
  int operator_applications = 0;
  int restarts = 0;
};

// `progress(applications)` is called after every 25th application of OP (long solves).
struct EigenSolveResult {
  Eigen::VectorXd values;   // ascending, rad^2/s^2
  Eigen::MatrixXd vectors;  // dimension x pairs, M-orthonormal
  EigenSolveStats stats;
};

// Throws ModalError naming `object` if the factorization fails, ARPACK reports an error, or
// fewer than the requested pairs converge.
EigenSolveResult solveLowestModes(const std::string& object, const Eigen::SparseMatrix<double>& stiffness,
                                  const Eigen::SparseMatrix<double>& mass, const EigenSolveSettings& settings,
                                  const std::function<void(int)>& progress = {});

}  // namespace thx::audio
