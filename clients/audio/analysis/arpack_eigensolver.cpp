#include "clients/audio/analysis/arpack_eigensolver.hpp"

#include <arpack/arpack.h>
#include <omp.h>
#include <time.h>

#include <Eigen/CholmodSupport>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <chrono>
#include <memory>
#include <numeric>
#include <vector>

#include "base/elapsed.hpp"
#include "base/number_text.hpp"
#include "clients/audio/analysis/modal_error.hpp"

namespace thx::audio {
namespace {

std::string arpackMessage(const char* routine, a_int info) {
  switch (info) {
    case 1: return std::string(routine) + ": maximum number of restarts reached";
    case 3: return std::string(routine) + ": no shifts could be applied (increase the Lanczos vectors)";
    case -9999: return std::string(routine) + ": could not build a Lanczos factorization";
    default: return std::string(routine) + " error code " + std::to_string(info);
  }
}

// (K - sigma M)^-1 applied to vectors: the factor behind it chosen by Factorization.
class ShiftedInverse {
 public:
  virtual ~ShiftedInverse() = default;
  virtual void solve(const Eigen::VectorXd& b, Eigen::Map<Eigen::VectorXd> x) = 0;
};

class SimplicialInverse : public ShiftedInverse {
 public:
  SimplicialInverse(const std::string& object, const Eigen::SparseMatrix<double>& a) : ldlt_(a) {
    const long n = long(a.rows());
    if (ldlt_.info() != Eigen::Success)
      throw ModalError(object + ": the factorization of K - sigma M failed (" + std::to_string(n) +
                       " DOFs): the mesh or material gives no positive-definite stiffness");
    if ((ldlt_.vectorD().array() <= 0).any())
      throw ModalError(object + ": K - sigma M is not positive definite: a negative shift should make it so; "
                       "check the material and the mesh");
  }
  void solve(const Eigen::VectorXd& b, Eigen::Map<Eigen::VectorXd> x) override { x = ldlt_.solve(b); }

 private:
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt_;
};

class CholmodInverse : public ShiftedInverse {
 public:
  CholmodInverse(const std::string& object, const Eigen::SparseMatrix<double>& a) {
    // Debian's CHOLMOD runs OpenMP threads: one thread keeps the solve off the other work of a
    // 2-CPU machine (the servo's) and its cost comparable with the simplicial factorization.
    omp_set_num_threads(1);
    llt_.compute(a);
    // A Cholesky factorization exists only for a positive-definite matrix, so failure says both.
    if (llt_.info() != Eigen::Success)
      throw ModalError(object + ": the factorization of K - sigma M failed (" + std::to_string(a.rows()) +
                       " DOFs): K - sigma M is not positive definite; a negative shift should make it so, "
                       "check the material and the mesh");
  }
  void solve(const Eigen::VectorXd& b, Eigen::Map<Eigen::VectorXd> x) override {
    solved_ = llt_.solve(b);
    x = solved_;
  }

 private:
  Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>> llt_;
  Eigen::VectorXd solved_;
};

}  // namespace

double processCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

EigenSolveResult solveLowestModes(const std::string& object, const Eigen::SparseMatrix<double>& stiffness,
                                  const Eigen::SparseMatrix<double>& mass, const EigenSolveSettings& settings,
                                  const std::function<void(int)>& progress) {
  const a_int n = a_int(stiffness.rows());
  const a_int nev = settings.eigenpairs;
  if (!(settings.shift < 0))
    throw ModalError(object + ": eigen solve shift " + numberText(settings.shift) +
                     ": expected a negative shift (K - sigma M must be positive definite)");
  if (nev < 1 || nev >= n)
    throw ModalError(object + ": " + std::to_string(nev) + " modes requested from " + std::to_string(n) +
                     " degrees of freedom: expected at least 1 and fewer than the DOFs (refine the mesh)");
  // At least 40 vectors beyond nev: with fewer, single-vector Lanczos can miss a copy of a
  // repeated eigenvalue (a symmetric mesh's pairs and triples; docs/audio.md §1).
  a_int ncv = settings.lanczos_vectors > 0 ? settings.lanczos_vectors : std::max(2 * nev + 1, nev + 40);
  ncv = std::min(ncv, n);
  if (ncv <= nev)
    throw ModalError(object + ": " + std::to_string(ncv) + " Lanczos vectors for " + std::to_string(nev) +
                     " modes: expected more vectors than modes");

  EigenSolveResult result;
  auto t0 = std::chrono::steady_clock::now();
  double cpu0 = processCpuSeconds();
  std::unique_ptr<ShiftedInverse> inverse;
  {
    const Eigen::SparseMatrix<double> shifted = stiffness - settings.shift * mass;
    if (settings.factorization == Factorization::SimplicialLdlt)
      inverse = std::make_unique<SimplicialInverse>(object, shifted);
    else
      inverse = std::make_unique<CholmodInverse>(object, shifted);
  }
  result.stats.factor_s = secondsSince(t0);
  result.stats.factor_cpu_s = processCpuSeconds() - cpu0;

  t0 = std::chrono::steady_clock::now();
  cpu0 = processCpuSeconds();
  a_int ido = 0, info = 0;
  const a_int lworkl = ncv * (ncv + 8);
  std::vector<double> resid(std::size_t(n), 0.0), v(std::size_t(n) * ncv), workd(std::size_t(3) * n),
      workl(static_cast<std::size_t>(lworkl));
  // A fixed start vector keeps the solve (and so the cache and the tests) deterministic.
  for (a_int i = 0; i < n; ++i) resid[std::size_t(i)] = 1.0 + 0.1 * double((i * 7919) % 101) / 101.0;
  info = 1;  // use resid as the start vector
  a_int iparam[11] = {0}, ipntr[14] = {0};
  iparam[0] = 1;  // exact shifts
  iparam[2] = settings.max_iterations;
  iparam[6] = 3;  // shift-invert
  Eigen::VectorXd tmp(n);
  for (;;) {
    dsaupd_c(&ido, "G", n, "LM", nev, settings.tolerance, resid.data(), ncv, v.data(), n, iparam, ipntr, workd.data(),
             workl.data(), lworkl, &info);
    if (ido == 99) break;
    double* x = workd.data() + ipntr[0] - 1;
    double* y = workd.data() + ipntr[1] - 1;
    Eigen::Map<Eigen::VectorXd> xv(x, n), yv(y, n);
    if (ido == -1) {
      tmp = mass * xv;
      inverse->solve(tmp, yv);
    } else if (ido == 1) {
      Eigen::Map<Eigen::VectorXd> bx(workd.data() + ipntr[2] - 1, n);  // M x, provided by ARPACK
      tmp = bx;
      inverse->solve(tmp, yv);
    } else if (ido == 2) {
      yv = mass * xv;
      continue;
    } else {
      throw ModalError(object + ": ARPACK asked for an unsupported operation (ido " + std::to_string(ido) + ")");
    }
    ++result.stats.operator_applications;
    if (progress && result.stats.operator_applications % 25 == 0) progress(result.stats.operator_applications);
  }
  result.stats.restarts = iparam[2];
  if (info < 0 || info == 3 || info == -9999)
    throw ModalError(object + ": eigen solve did not converge (" + arpackMessage("dsaupd", info) + ", " +
                     std::to_string(n) + " DOFs, " + std::to_string(nev) + " modes)");
  const a_int converged = iparam[4];
  if (info == 1 || converged < nev)
    throw ModalError(object + ": eigen solve did not converge: " + std::to_string(converged) + " of " +
                     std::to_string(nev) + " modes after " + std::to_string(iparam[2]) +
                     " restarts (raise the iteration limit or the tolerance)");

  std::vector<a_int> select(static_cast<std::size_t>(ncv), 0);
  std::vector<double> d(static_cast<std::size_t>(nev));
  Eigen::MatrixXd z(n, nev);
  a_int info_e = 0;
  dseupd_c(1, "A", select.data(), d.data(), z.data(), n, settings.shift, "G", n, "LM", nev, settings.tolerance,
           resid.data(), ncv, v.data(), n, iparam, ipntr, workd.data(), workl.data(), lworkl, &info_e);
  if (info_e != 0)
    throw ModalError(object + ": eigenvector extraction failed (" + arpackMessage("dseupd", info_e) + ")");
  result.stats.iterate_s = secondsSince(t0);
  result.stats.iterate_cpu_s = processCpuSeconds() - cpu0;

  std::vector<int> order(static_cast<std::size_t>(nev));
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return d[std::size_t(a)] < d[std::size_t(b)]; });
  result.values.resize(nev);
  result.vectors.resize(n, nev);
  for (a_int k = 0; k < nev; ++k) {
    result.values[k] = d[std::size_t(order[std::size_t(k)])];
    result.vectors.col(k) = z.col(order[std::size_t(k)]);
  }
  return result;
}

}  // namespace thx::audio
