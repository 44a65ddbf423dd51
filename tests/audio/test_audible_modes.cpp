// Damping, band and the psychoacoustic merge (audible_modes.hpp) on solved objects.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "clients/audio/audible_modes.hpp"
#include "tests/audio/modal_fixtures.hpp"

namespace thx::audio {
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
  // The merged shape is the sum of the members': its modal impulse is theirs summed.
  EXPECT_LT((a.shapes.col(0) - s.shapes.leftCols(5).rowwise().sum()).cwiseAbs().maxCoeff(), 1e-12);
  // Zero thresholds merge nothing.
  AudibleOptions none;
  none.merge_abs_hz = 0;
  none.merge_rel = 0;
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
  o.max_modes = 3;
  a = audibleModes(s, steel(), o);
  EXPECT_EQ(a.size(), 3u);
  EXPECT_EQ(a.truncated, 7);
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
}  // namespace thx::audio
