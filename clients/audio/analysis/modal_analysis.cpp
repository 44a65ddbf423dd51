#include "clients/audio/analysis/modal_analysis.hpp"

#include <chrono>
#include <cmath>
#include <numbers>

#include "base/elapsed.hpp"
#include "base/number_text.hpp"
#include "clients/audio/analysis/arpack_eigensolver.hpp"
#include "clients/audio/analysis/fem_assembly.hpp"
#include "clients/audio/analysis/modal_cache.hpp"
#include "clients/audio/analysis/modal_error.hpp"
#include "clients/audio/analysis/observation.hpp"

namespace thx::audio {

double signedHz(double lambda) {
  return std::copysign(std::sqrt(std::fabs(lambda)), lambda) / (2.0 * std::numbers::pi);
}

EigenSolveSettings eigenSolveSettings(const ModalSettings& settings, int rigid) {
  EigenSolveSettings es;
  es.eigenpairs = settings.elastic_modes + rigid;
  es.lanczos_vectors = settings.lanczos_vectors;
  es.shift = -std::pow(2.0 * std::numbers::pi * settings.shift_hz, 2);
  es.tolerance = settings.tolerance;
  es.max_iterations = settings.max_iterations;
  es.factorization = settings.factorization;
  return es;
}

int rigidModeCount(const EigenSolveResult& r, const ModalSettings& settings) {
  int rigid = 0;
  while (rigid < r.values.size() && signedHz(r.values[rigid]) < settings.rigid_below_hz) ++rigid;
  return rigid;
}

void takeModes(const EigenSolveResult& r, int rigid, const std::vector<int>& free_dof, ModalSolution& s) {
  s.factor_s = r.stats.factor_s;
  s.iterate_s = r.stats.iterate_s;
  s.factor_cpu_s = r.stats.factor_cpu_s;
  s.iterate_cpu_s = r.stats.iterate_cpu_s;
  s.operator_applications = r.stats.operator_applications;
  s.rigid_modes = rigid;
  s.rigid_hz.resize(rigid);
  for (int k = 0; k < rigid; ++k) s.rigid_hz[k] = signedHz(r.values[k]);
  const int elastic = int(r.values.size()) - rigid;
  s.omega_rad_per_s.resize(elastic);
  s.shapes = Eigen::MatrixXd::Zero(s.mesh_dofs, elastic);
  for (int k = 0; k < elastic; ++k) {
    s.omega_rad_per_s[k] = std::sqrt(r.values[rigid + k]);
    for (std::size_t i = 0; i < free_dof.size(); ++i)
      if (free_dof[i] >= 0) s.shapes(Eigen::Index(i), k) = r.vectors(free_dof[i], rigid + k);
  }
}

double ModalSolution::frequencyHz(int mode) const { return omega_rad_per_s[mode] / (2.0 * std::numbers::pi); }

Eigen::MatrixXd freeRows(const Eigen::MatrixXd& full, const std::vector<int>& free_dof, int free_count) {
  Eigen::MatrixXd out(free_count, full.cols());
  for (std::size_t i = 0; i < free_dof.size(); ++i)
    if (free_dof[i] >= 0) out.row(free_dof[i]) = full.row(Eigen::Index(i));
  return out;
}

ModalSolution analyse(const TetMesh& mesh, const ElasticMaterial& material, const ModalSettings& settings,
                      const AnalysisOptions& options) {
  const auto t_start = std::chrono::steady_clock::now();
  auto say = [&](const std::string& line) {
    if (options.progress) options.progress(mesh.name + ": " + line);
  };
  checkMaterial(mesh.name, material);
  if (settings.elastic_modes < 1)
    throw ModalError(mesh.name + ": " + std::to_string(settings.elastic_modes) + " modes requested: expected >= 1");
  if (!(settings.shift_hz > 0))
    throw ModalError(mesh.name + ": shift " + numberText(settings.shift_hz) + " Hz: expected > 0 (sigma = -(2 pi f)^2)");

  // The listener first: a mesh with nowhere to listen fails before any solve.
  const Eigen::VectorXd w = observationVector(mesh);

  std::uint64_t key = 0;
  std::string cache_path;
  if (options.cache_dir) {
    key = modalCacheKey(mesh, material, settings);
    cache_path = modalCachePath(*options.cache_dir, key);
    if (auto cached = readModalCache(cache_path, key, options.progress)) {
      cached->observation = cached->shapes.transpose() * w;
      cached->total_s = secondsSince(t_start);
      say("modes read from the cache " + cache_path);
      return *cached;
    }
  }

  const bool free_body = !mesh.anyClamped();
  say("assembling " + std::to_string(mesh.tets.size()) + (mesh.order == ElementOrder::Linear ? " Tet4" : " Tet10") +
      " elements, " + std::to_string(mesh.dofCount()) + " DOFs");
  auto t0 = std::chrono::steady_clock::now();
  const double cpu0 = processCpuSeconds();
  const AssembledSystem sys = assemble(mesh, material);
  ModalSolution s;
  s.assemble_s = secondsSince(t0);
  s.assemble_cpu_s = processCpuSeconds() - cpu0;
  s.mesh_dofs = mesh.dofCount();
  s.free_dofs = sys.free_count;

  const EigenSolveSettings es = eigenSolveSettings(settings, free_body ? 6 : 0);
  say("factorizing K - sigma M and iterating (ARPACK, " + std::to_string(es.eigenpairs) + " modes)");
  // At most one progress line a second: only long solves show their Lanczos steps.
  auto last_line = std::chrono::steady_clock::now();
  const EigenSolveResult r = solveLowestModes(mesh.name, sys.stiffness, sys.mass, es, [&](int applications) {
    if (secondsSince(last_line) < 1.0) return;
    last_line = std::chrono::steady_clock::now();
    say("  " + std::to_string(applications) + " Lanczos steps");
  });

  const int rigid = rigidModeCount(r, settings);
  const int expected = free_body ? 6 : 0;
  if (rigid != expected) {
    std::string list;
    for (int k = 0; k < std::min<int>(rigid + 1, int(r.values.size())); ++k)
      list += (k ? ", " : "") + numberText(signedHz(r.values[k]));
    throw ModalError(mesh.name + ": " + std::to_string(rigid) + " modes below " + numberText(settings.rigid_below_hz) +
                     " Hz (" + list + " Hz): expected " + std::to_string(expected) +
                     (free_body ? " rigid-body modes for a free body (is the mesh in several pieces?)"
                                : " for a held body (is it held at enough nodes?)"));
  }
  takeModes(r, rigid, sys.free_dof, s);
  s.observation = s.shapes.transpose() * w;
  if (options.cache_dir) {
    writeModalCache(cache_path, key, s);
    s.cache_file = cache_path;
  }
  s.total_s = secondsSince(t_start);
  say("done in " + numberText(s.total_s) + " s (factor " + numberText(s.factor_s) + " s, iterate " +
      numberText(s.iterate_s) + " s; CPU: assemble " + numberText(s.assemble_cpu_s) + " s, factor " +
      numberText(s.factor_cpu_s) + " s, iterate " + numberText(s.iterate_cpu_s) + " s, " +
      std::to_string(s.operator_applications) + " applications of OP)");
  return s;
}

}  // namespace thx::audio
