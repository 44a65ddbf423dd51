#include "clients/study/trial_plan.hpp"

#include <cmath>
#include <numbers>
#include <utility>

namespace thx::study {

std::uint64_t StudyRng::next() {
  std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

int StudyRng::below(int n) {
  if (n <= 1) return 0;
  const std::uint64_t un = std::uint64_t(n);
  const std::uint64_t limit = ~std::uint64_t{0} - (~std::uint64_t{0} % un);  // multiple of n
  std::uint64_t x;
  do x = next(); while (x >= limit);
  return int(x % un);
}

double StudyRng::uniform() { return double(next() >> 11) * 0x1.0p-53; }

double StudyRng::gaussian() {
  const double u1 = 1.0 - uniform();  // (0, 1]
  const double u2 = uniform();
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
}

namespace {
template <class T>
void shuffle(std::vector<T>& v, StudyRng& rng) {  // Fisher-Yates
  for (int i = int(v.size()) - 1; i > 0; --i) std::swap(v[std::size_t(i)], v[std::size_t(rng.below(i + 1))]);
}
}  // namespace

std::vector<PlannedTrial> planIdentification(const StudyManifest& m, std::uint64_t seed) {
  StudyRng rng(seed);
  std::vector<Cues> removed{{false, true, true}, {true, false, true}, {true, true, false}};
  shuffle(removed, rng);
  std::vector<Cues> cues{Cues{}, Cues{}, Cues{}};
  cues.insert(cues.end(), removed.begin(), removed.end());
  std::vector<PlannedTrial> plan;
  const int n = int(m.surfaces.size());
  for (std::size_t i = 0; i < cues.size(); ++i) {
    PlannedTrial t;
    t.trial = int(i) + 1;
    t.surface = rng.below(n);
    t.scene = m.surfaces[std::size_t(t.surface)].scene;
    t.cues = cues[i];
    t.first_look = rng.below(n);
    plan.push_back(t);
  }
  return plan;
}

std::vector<PlannedTrial> planReliefVsNormal(const StudyManifest& m, std::uint64_t seed) {
  StudyRng rng(seed);
  const int n = int(m.surfaces.size());
  std::vector<int> which(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) which[std::size_t(i)] = i;
  shuffle(which, rng);  // the first half become relief maps
  std::vector<bool> relief(std::size_t(n), false);
  for (int i = 0; i < n / 2; ++i) relief[std::size_t(which[std::size_t(i)])] = true;
  std::vector<int> order = which;
  shuffle(order, rng);  // the order they are offered in, independent of the split
  std::vector<PlannedTrial> plan;
  for (int k = 0; k < n; ++k) {
    PlannedTrial t;
    t.trial = k + 1;
    t.surface = order[std::size_t(k)];
    const auto& s = m.surfaces[std::size_t(t.surface)];
    t.representation = relief[std::size_t(t.surface)] ? Representation::Relief : Representation::Normal;
    t.scene = t.representation == Representation::Relief ? s.relief : s.normal;
    plan.push_back(t);
  }
  return plan;
}

std::vector<PlannedTrial> planSession(const StudyManifest& m, std::uint64_t seed) {
  return m.study == Study::Identification ? planIdentification(m, seed) : planReliefVsNormal(m, seed);
}

}  // namespace thx::study
