#pragma once
// From an object's FEM modes to the modes worth synthesising: Rayleigh damping (Eq. 4,
// C = alpha M + beta K, so d = (alpha + beta omega^2) / 2 and omega_d = omega sqrt(1 - xi^2)),
// the audible band, the psychoacoustic merge of modes closer than the frequency-discrimination
// threshold (Raghuvanshi & Lin 2006; docs/audio.md §8.6) and truncation to a mode budget.
// Each mode is heard through the body's listener w (observation.hpp), and a merge sums the modes'
// contributions, not their shapes, so the result does not depend on the basis the eigensolver
// chose inside a repeated eigenvalue's subspace (docs/audio.md §9a).
#include <Eigen/Core>
#include <vector>

#include "clients/audio/analysis/elastic_material.hpp"
#include "clients/audio/analysis/modal_analysis.hpp"

namespace thx::audio {

struct AudibleOptions {
  double min_hz = 20.0;
  double max_hz = 16000.0;        // also always below the Nyquist frequency
  double sample_rate_hz = 44100.0;
  bool merge = true;
  // Two modes are indistinguishable when their frequencies differ by less than
  // max(merge_abs_hz, merge_rel * f) (pure-tone difference limens, docs/audio.md §8.6).
  double merge_abs_hz = 2.0;
  double merge_rel = 0.003;
  // Keep at most this many (the lowest) after merging; 0 = all. Copies of a repeated mode are
  // kept or dropped together (the cut moves below them), so the sound stays basis-invariant.
  int max_modes = 0;
};

struct AudibleModes {
  std::vector<double> frequency_hz;  // damped frequency omega_d / 2 pi, ascending
  std::vector<double> decay_per_s;   // d: the envelope is exp(-d t)
  std::vector<double> damping_ratio; // xi = d / omega
  std::vector<int> members;          // FEM modes merged into this one (1 = not merged)
  // Mesh DOFs x modes: the observed shape of each, sum over its members m of u_m (w . u_m) with
  // u_m M-orthonormal, so a force (impulse) J at a node drives it by shapes.row(dof) * J =
  // sum_m (J . u_m)(w . u_m): what the listener hears of that strike per unit modal response.
  // For the members spanning a subspace that is J^T P w with P = U U^T, whatever basis U.
  Eigen::MatrixXd shapes;
  int dropped_overdamped = 0, dropped_out_of_band = 0, merged_away = 0, truncated = 0;

  std::size_t size() const { return frequency_hz.size(); }
};

// Two modes this close (relative) are copies of one repeated eigenvalue (a symmetry's degenerate
// subspace; the solver's copies agree to ~1e-11): never split between groups or by truncation.
inline constexpr double kRepeatedModeRel = 1e-7;

// The discrimination threshold at frequency f.
double mergeThresholdHz(const AudibleOptions& options, double f_hz);

// Throws std::logic_error (a caller's mistake) when solution.observation does not hold one value
// per mode.
AudibleModes audibleModes(const ModalSolution& solution, const ElasticMaterial& material, const AudibleOptions& options);

}  // namespace thx::audio
