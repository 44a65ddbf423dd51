#include "clients/audio/analysis/audible_modes.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace thx::audio {

double mergeThresholdHz(const AudibleOptions& o, double f_hz) { return std::max(o.merge_abs_hz, o.merge_rel * f_hz); }

AudibleModes audibleModes(const ModalSolution& s, const ElasticMaterial& m, const AudibleOptions& o) {
  if (s.observation.size() != s.omega_rad_per_s.size())
    throw std::logic_error("audibleModes: " + std::to_string(s.observation.size()) + " observation values for " +
                                std::to_string(s.omega_rad_per_s.size()) + " modes (analyse() fills them)");
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

  // Groups of consecutive modes within the threshold of the group's lowest frequency; copies of
  // a repeated mode always share a group (even with merge off), so no group boundary can cut
  // through a degenerate subspace.
  auto repeated = [](const Candidate& a, const Candidate& b) { return b.f_hz - a.f_hz <= kRepeatedModeRel * b.f_hz; };
  std::vector<std::vector<Candidate>> groups;
  for (const Candidate& c : kept) {
    if (!groups.empty() && (repeated(groups.back().back(), c) ||
                            (o.merge && c.f_hz - groups.back().front().f_hz < mergeThresholdHz(o, groups.back().front().f_hz))))
      groups.back().push_back(c);
    else
      groups.push_back({c});
  }
  if (o.merge) out.merged_away = int(kept.size() - groups.size());
  if (o.max_modes > 0) {
    // Each group becomes one audible mode, except with merge off: then each of its members does
    // (the copies of a repeated mode, all with one frequency).
    std::size_t g = 0;
    int count = 0;
    for (; g < groups.size(); ++g) {
      const int n = o.merge ? 1 : int(groups[g].size());
      if (count + n > o.max_modes) break;
      count += n;
    }
    for (std::size_t k = g; k < groups.size(); ++k) out.truncated += o.merge ? 1 : int(groups[k].size());
    groups.resize(g);
  }
  // Each audible mode's members: a whole group when merging, else one mode each.
  std::vector<std::vector<Candidate>> audible;
  for (auto& group : groups) {
    if (o.merge) {
      audible.push_back(std::move(group));
    } else {
      for (const Candidate& c : group) audible.push_back({c});
    }
  }
  out.shapes = Eigen::MatrixXd::Zero(s.shapes.rows(), Eigen::Index(audible.size()));
  for (std::size_t g = 0; g < audible.size(); ++g) {
    double f = 0, d = 0, xi = 0;
    for (const Candidate& c : audible[g]) {
      f += c.f_hz, d += c.decay, xi += c.xi;
      // The member's contribution, not its shape: invariant under any orthogonal change of basis
      // among the group's members, and under a member's sign.
      out.shapes.col(Eigen::Index(g)) += s.shapes.col(c.mode) * s.observation[c.mode];
    }
    const double n = double(audible[g].size());
    out.frequency_hz.push_back(f / n);
    out.decay_per_s.push_back(d / n);
    out.damping_ratio.push_back(xi / n);
    out.members.push_back(int(audible[g].size()));
  }
  return out;
}

}  // namespace thx::audio
