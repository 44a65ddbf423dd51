#include "clients/study/participant_model.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace thx::study {
namespace {

int clampRound(double x, int lo, int hi) { return std::clamp(int(std::lround(x)), lo, hi); }

// Squared JND distance over the features of `cue` that `perceived` carries.
std::pair<double, int> cueDistance(const std::array<std::optional<double>, kFeatureCount>& perceived,
                                   const Percept& expected, Cue cue) {
  double d = 0.0;
  int n = 0;
  for (int f = 0; f < kFeatureCount; ++f) {
    if (cueOf(f) != cue || !perceived[std::size_t(f)] || !expected.features[std::size_t(f)]) continue;
    const double z = (*perceived[std::size_t(f)] - *expected.features[std::size_t(f)]) / kFeatureJnd[std::size_t(f)];
    d += z * z;
    ++n;
  }
  return {d, n};
}

constexpr std::array<Cue, 3> kCues{Cue::Sound, Cue::Ball, Cue::Pen};

int matchRating(double r, int n) { return n == 0 ? 1 : clampRound(1.0 + 9.0 * std::exp(-r / (2.0 * n)), 1, 10); }

}  // namespace

std::array<std::optional<double>, kFeatureCount> SimulatedParticipant::perceive(const Percept& p) {
  std::array<std::optional<double>, kFeatureCount> out{};
  for (int f = 0; f < kFeatureCount; ++f) {
    const double noise = rng_.gaussian();  // drawn for every feature, so removing a cue shifts no other draw
    if (p.features[std::size_t(f)]) out[std::size_t(f)] = *p.features[std::size_t(f)] + noise_ * kFeatureJnd[std::size_t(f)] * noise;
  }
  return out;
}

IdentificationAnswer SimulatedParticipant::identify(const Percept& presented, const std::vector<Percept>& expected) {
  const auto perceived = perceive(presented);
  IdentificationAnswer a;
  for (const Percept& e : expected) {
    double d = 0.0;
    for (Cue c : kCues) d += cueDistance(perceived, e, c).first;
    a.distances.push_back(d);
  }
  // Ties (candidates the carried features cannot tell apart) are broken at random, not by order.
  const double best = *std::min_element(a.distances.begin(), a.distances.end());
  std::vector<int> tied;
  for (std::size_t c = 0; c < a.distances.size(); ++c)
    if (a.distances[c] <= best + 1e-9 * (1.0 + best)) tied.push_back(int(c));
  a.answer = tied[std::size_t(rng_.below(int(tied.size())))];
  std::vector<double> sorted = a.distances;
  std::sort(sorted.begin(), sorted.end());
  const double d1 = sorted[0], d2 = sorted.size() > 1 ? sorted[1] : sorted[0];
  a.ease = clampRound(1.0 + 9.0 * (d2 - d1) / (d2 + d1 + 1e-12), 1, 10);

  std::array<double, 3> sep{};
  for (int f = 0; f < kFeatureCount; ++f) {
    if (!perceived[std::size_t(f)]) continue;
    double mean = 0.0, m2 = 0.0;
    for (const Percept& e : expected) mean += e.features[std::size_t(f)].value_or(0.0);
    mean /= double(expected.size());
    for (const Percept& e : expected) m2 += std::pow(e.features[std::size_t(f)].value_or(0.0) - mean, 2);
    sep[std::size_t(cueOf(f))] += m2 / double(expected.size()) / std::pow(kFeatureJnd[std::size_t(f)], 2);
  }
  const double max_sep = *std::max_element(sep.begin(), sep.end());
  for (Cue c : kCues) {
    const auto [r, n] = cueDistance(perceived, expected[std::size_t(a.answer)], c);
    if (n == 0) continue;  // removed: not rated
    const std::size_t k = std::size_t(c);
    a.use[k] = max_sep > 0 ? clampRound(1.0 + 4.0 * sep[k] / max_sep, 1, 5) : 1;
    a.accuracy[k] = matchRating(r, n);
  }
  return a;
}

SurfaceRatings SimulatedParticipant::rate(const Percept& presented, const Percept& relief_version, Representation shown) {
  const auto perceived = perceive(presented);
  SurfaceRatings s;
  const auto m = [&](Cue c) {
    const auto [r, n] = cueDistance(perceived, relief_version, c);
    return matchRating(r, n);
  };
  s.match_physics = m(Cue::Ball);
  s.match_sound = m(Cue::Sound);
  s.match_haptics = m(Cue::Pen);
  s.realism = clampRound(5.0 + (shown == Representation::Relief ? 3.0 : 0.0) + noise_ * rng_.gaussian(), 1, 10);
  s.overall = clampRound((s.realism + s.match_physics + s.match_sound + s.match_haptics) / 4.0, 1, 10);
  return s;
}

}  // namespace thx::study
