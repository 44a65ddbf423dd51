// Damping, band and the psychoacoustic merge (audible_modes.hpp) on solved objects.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "clients/audio/analysis/audible_modes.hpp"
#include "tests/audio/modal_fixtures.hpp"

namespace thx::audio::test_audible_modes {
namespace {

using test::relativeError;
using test::steel;

// a = 0.1 m: T2 near 12.5 kHz, S2 near 13.2 kHz (docs/audio.md §8.3), both in band.
// Solved once for all tests of this file.
const ModalSolution& sphere10() {
  static const ModalSolution solution = [] {
    ModalSettings s;
    s.elastic_modes = 10;
    return analyse(sphereMesh("sphere", 0.1, 4, ElementOrder::Quadratic), steel(), s);
  }();
  return solution;
}

TEST(AudibleModes, RayleighDampingGivesDecayAndDampedFrequency) {
  const ModalSolution s = sphere10();
  AudibleOptions o;
  o.merge = false;
  const AudibleModes a = audibleModes(s, steel(), o);
  ASSERT_EQ(a.size(), 10u);
  for (std::size_t k = 0; k < a.size(); ++k) {
    const double w = s.omega_rad_per_s[Eigen::Index(k)];
    const double d = 0.5 * (steel().rayleigh_alpha_per_s + steel().rayleigh_beta_s * w * w);
    EXPECT_NEAR(a.decay_per_s[k], d, 1e-12 * d);
    EXPECT_NEAR(a.frequency_hz[k], w * std::sqrt(1 - (d / w) * (d / w)) / (2 * std::numbers::pi), 1e-9 * w);
    EXPECT_EQ(a.members[k], 1);
  }
}

// The structured sphere splits T2 and S2 into 2 + 3 modes about 0.2 % apart, well inside the
// discrimination threshold; T2 and S2 themselves are 5.6 % apart.
TEST(AudibleModes, MergeJoinsEachFiveFoldFamilyIntoOneMode) {
  const ModalSolution s = sphere10();
  const AudibleModes a = audibleModes(s, steel(), AudibleOptions{});
  ASSERT_EQ(a.size(), 2u);
  EXPECT_EQ(a.members[0], 5);
  EXPECT_EQ(a.members[1], 5);
  EXPECT_EQ(a.merged_away, 8);
  // The merged column is the sum of the members' contributions u_m (w . u_m) (observation.hpp):
  // what the listener hears of a strike is theirs summed.
  const Eigen::VectorXd five = s.shapes.leftCols(5) * s.observation.head(5);
  EXPECT_LT((a.shapes.col(0) - five).cwiseAbs().maxCoeff(), 1e-12 * five.cwiseAbs().maxCoeff());
  // Zero thresholds merge only the exact copies of a repeated mode (2 + 3 per family on this
  // mesh), which share one frequency: merging them changes no sample.
  AudibleOptions none;
  none.merge_abs_hz = 0;
  none.merge_rel = 0;
  const AudibleModes copies = audibleModes(s, steel(), none);
  ASSERT_EQ(copies.size(), 4u);
  const int members[4] = {2, 3, 3, 2};  // T2 splits 2 below 3, S2 3 below 2
  for (std::size_t k = 0; k < copies.size(); ++k) EXPECT_EQ(copies.members[k], members[k]) << k;
  none.merge = false;
  EXPECT_EQ(audibleModes(s, steel(), none).size(), 10u);
}

TEST(AudibleModes, BandAndTruncationDropModes) {
  const ModalSolution s = sphere10();
  AudibleOptions o;
  o.merge = false;
  o.max_hz = 13000;  // between T2 and S2
  AudibleModes a = audibleModes(s, steel(), o);
  EXPECT_EQ(a.size(), 5u);
  EXPECT_EQ(a.dropped_out_of_band, 5);
  o.max_hz = 16000;
  o.sample_rate_hz = 22050;  // Nyquist 11 025 Hz: nothing left
  EXPECT_EQ(audibleModes(s, steel(), o).size(), 0u);
  o.sample_rate_hz = 44100;
  // A budget of 3 would cut T2's second set of copies (modes 3-5): the cut moves below all of
  // them (a repeated mode is kept or dropped whole, so the sound stays basis-invariant).
  o.max_modes = 3;
  a = audibleModes(s, steel(), o);
  EXPECT_EQ(a.size(), 2u);
  EXPECT_EQ(a.truncated, 8);
  o.max_modes = 5;
  EXPECT_EQ(audibleModes(s, steel(), o).size(), 5u);
}

TEST(AudibleModes, OverdampedModesAreDropped) {
  const ModalSolution s = sphere10();
  ElasticMaterial m = steel();
  m.rayleigh_beta_s = 1e-3;  // xi = beta omega / 2 >> 1 at 12 kHz
  const AudibleModes a = audibleModes(s, m, AudibleOptions{});
  EXPECT_EQ(a.size(), 0u);
  EXPECT_EQ(a.dropped_overdamped, 10);
}

}  // namespace
}  // namespace thx::audio::test_audible_modes
