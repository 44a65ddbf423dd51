#include "clients/audio/analysis/spring_mass.hpp"

#include <chrono>
#include <cmath>
#include <numbers>

#include "base/number_text.hpp"
#include "clients/audio/analysis/arpack_eigensolver.hpp"
#include "clients/audio/analysis/modal_error.hpp"

namespace thx::audio {
SpringMassLattice surfaceLattice(const std::string& name, double extent_x, double extent_y, double thickness,
                                 int nodes, const ElasticMaterial& m, bool clamp_edges) {
  checkMaterial(name, m);
  if (nodes < 2) throw ModalError(name + ": " + std::to_string(nodes) + " lattice nodes per side: expected >= 2");
  if (!(extent_x > 0 && extent_y > 0 && thickness > 0))
    throw ModalError(name + ": surface " + numberText(extent_x) + " x " + numberText(extent_y) + " x " +
                     numberText(thickness) + " m: expected every size > 0");
  SpringMassLattice l;
  l.name = name;
  l.nx = l.ny = nodes;
  const double dx = extent_x / (nodes - 1), dy = extent_y / (nodes - 1);
  l.mass_kg = m.density_kg_per_m3 * thickness * dx * dy;
  l.spring_n_per_m = m.youngs_modulus_pa * thickness;
  l.clamp_edges = clamp_edges;
  return l;
}

SpringMassSystem assembleSpringMass(const SpringMassLattice& l) {
  if (l.nx < 2 || l.ny < 1)
    throw ModalError(l.name + ": lattice " + std::to_string(l.nx) + " x " + std::to_string(l.ny) +
                     " nodes: expected nx >= 2 and ny >= 1");
  if (!(l.mass_kg > 0 && std::isfinite(l.mass_kg)) || !(l.spring_n_per_m > 0 && std::isfinite(l.spring_n_per_m)))
    throw ModalError(l.name + ": node mass " + numberText(l.mass_kg) + " kg, spring " + numberText(l.spring_n_per_m) +
                     " N/m: expected both finite and > 0");
  const int nodes = l.nx * l.ny;
  auto held = [&](int i, int j) {
    return l.clamp_edges && (i == 0 || i == l.nx - 1 || (l.ny > 1 && (j == 0 || j == l.ny - 1)));
  };
  SpringMassSystem s;
  s.free_dof.assign(std::size_t(nodes), -1);
  for (int j = 0; j < l.ny; ++j)
    for (int i = 0; i < l.nx; ++i)
      if (!held(i, j)) s.free_dof[std::size_t(j * l.nx + i)] = s.free_count++;
  if (s.free_count == 0) throw ModalError(l.name + ": every lattice node is held: nothing can vibrate");

  // Each edge adds k to both ends' diagonals and -k off the diagonal; a held end keeps only the
  // free end's diagonal term (the spring still pulls it towards the held node).
  std::vector<Eigen::Triplet<double>> k;
  k.reserve(std::size_t(5 * nodes));
  const double ks = l.spring_n_per_m;
  auto edge = [&](int a, int b) {
    const int ra = s.free_dof[std::size_t(a)], rb = s.free_dof[std::size_t(b)];
    if (ra >= 0) k.emplace_back(ra, ra, ks);
    if (rb >= 0) k.emplace_back(rb, rb, ks);
    if (ra >= 0 && rb >= 0) {
      k.emplace_back(ra, rb, -ks);
      k.emplace_back(rb, ra, -ks);
    }
  };
  for (int j = 0; j < l.ny; ++j)
    for (int i = 0; i < l.nx; ++i) {
      const int n = j * l.nx + i;
      if (i + 1 < l.nx) edge(n, n + 1);
      if (j + 1 < l.ny) edge(n, n + l.nx);
    }
  s.stiffness.resize(s.free_count, s.free_count);
  s.stiffness.setFromTriplets(k.begin(), k.end());
  s.mass.resize(s.free_count, s.free_count);
  std::vector<Eigen::Triplet<double>> m;
  m.reserve(std::size_t(s.free_count));
  for (int r = 0; r < s.free_count; ++r) m.emplace_back(r, r, l.mass_kg);
  s.mass.setFromTriplets(m.begin(), m.end());
  return s;
}

ModalSolution springMassModes(const SpringMassLattice& l, const ModalSettings& settings) {
  const auto t0 = std::chrono::steady_clock::now();
  if (settings.elastic_modes < 1)
    throw ModalError(l.name + ": " + std::to_string(settings.elastic_modes) + " modes requested: expected >= 1");
  if (!(settings.shift_hz > 0))
    throw ModalError(l.name + ": shift " + numberText(settings.shift_hz) + " Hz: expected > 0 (sigma = -(2 pi f)^2)");
  const SpringMassSystem sys = assembleSpringMass(l);
  const bool free_body = !l.clamp_edges;
  const int rigid_expected = free_body ? 1 : 0;
  const EigenSolveSettings es = eigenSolveSettings(settings, rigid_expected);
  if (es.eigenpairs >= sys.free_count)
    throw ModalError(l.name + ": " + std::to_string(settings.elastic_modes) + " modes requested of a lattice with " +
                     std::to_string(sys.free_count) + " free nodes: expected fewer than " +
                     std::to_string(sys.free_count - rigid_expected));
  const EigenSolveResult r = solveLowestModes(l.name, sys.stiffness, sys.mass, es);

  ModalSolution s;
  s.mesh_dofs = int(sys.free_dof.size());
  s.free_dofs = sys.free_count;
  const int rigid = rigidModeCount(r, settings);
  if (rigid != rigid_expected)
    throw ModalError(l.name + ": " + std::to_string(rigid) + " modes below " + numberText(settings.rigid_below_hz) +
                     " Hz: expected " + std::to_string(rigid_expected) +
                     (free_body ? " (the free lattice's uniform translation)" : " (a held lattice has none)"));
  takeModes(r, rigid, sys.free_dof, s);
  s.total_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return s;
}

}  // namespace thx::audio
