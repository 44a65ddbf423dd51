#include "clients/audio/audible_modes.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace thx::audio {

double mergeThresholdHz(const AudibleOptions& o, double f_hz) { return std::max(o.merge_abs_hz, o.merge_rel * f_hz); }

AudibleModes audibleModes(const ModalSolution& s, const ElasticMaterial& m, const AudibleOptions& o) {
  const double two_pi = 2.0 * std::numbers::pi;
  const double max_hz = std::min(o.max_hz, 0.5 * o.sample_rate_hz);
  struct Candidate {
    double f_hz, decay, xi;
    int mode;
  };
  AudibleModes out;
  std::vector<Candidate> kept;
  for (int k = 0; k < s.omega_rad_per_s.size(); ++k) {
    const double w = s.omega_rad_per_s[k];
    const double d = 0.5 * (m.rayleigh_alpha_per_s + m.rayleigh_beta_s * w * w);
    const double xi = d / w;
    if (xi >= 1.0) {
      ++out.dropped_overdamped;
      continue;
    }
    const double f = w * std::sqrt(1.0 - xi * xi) / two_pi;
    // Nyquist itself is excluded: a mode there cannot be represented.
    if (f < o.min_hz || f > max_hz || f >= 0.5 * o.sample_rate_hz) {
      ++out.dropped_out_of_band;
      continue;
    }
    kept.push_back({f, d, xi, k});
  }
  std::sort(kept.begin(), kept.end(), [](const Candidate& a, const Candidate& b) { return a.f_hz < b.f_hz; });

  // Groups of consecutive modes within the threshold of the group's lowest frequency.
  std::vector<std::vector<Candidate>> groups;
  for (const Candidate& c : kept) {
    if (o.merge && !groups.empty() && c.f_hz - groups.back().front().f_hz < mergeThresholdHz(o, groups.back().front().f_hz))
      groups.back().push_back(c);
    else
      groups.push_back({c});
  }
  out.merged_away = int(kept.size() - groups.size());
  if (o.max_modes > 0 && int(groups.size()) > o.max_modes) {
    out.truncated = int(groups.size()) - o.max_modes;
    groups.resize(std::size_t(o.max_modes));
  }
  out.shapes = Eigen::MatrixXd::Zero(s.shapes.rows(), Eigen::Index(groups.size()));
  for (std::size_t g = 0; g < groups.size(); ++g) {
    double f = 0, d = 0, xi = 0;
    for (const Candidate& c : groups[g]) {
      f += c.f_hz, d += c.decay, xi += c.xi;
      out.shapes.col(Eigen::Index(g)) += s.shapes.col(c.mode);
    }
    const double n = double(groups[g].size());
    out.frequency_hz.push_back(f / n);
    out.decay_per_s.push_back(d / n);
    out.damping_ratio.push_back(xi / n);
    out.members.push_back(int(groups[g].size()));
  }
  return out;
}

}  // namespace thx::audio
