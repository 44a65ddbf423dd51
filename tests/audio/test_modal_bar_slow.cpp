// The converged sizes of the steel bar (docs/audio.md §8.1, §8.4): label `slow`.
#include <gtest/gtest.h>

#include <cstdio>

#include "clients/audio/analysis/modal_analysis.hpp"
#include "tests/audio/modal_fixtures.hpp"

namespace thx::audio::test_modal_bar_slow {
namespace {

using test::relativeError;
using test::kBarConverged;
using test::solveBar;

TEST(ModalBarSlow, Tet10TwoLayersAllSixModesWithinOnePercent) {
  const ModalSolution s = solveBar(2, ElementOrder::Quadratic, 6);
  EXPECT_EQ(s.mesh_dofs, 16335);
  for (int k = 0; k < 6; ++k) {
    std::printf("mode %d: %.1f Hz (converged %.1f, %+.3f %%)\n", k + 7, s.frequencyHz(k), kBarConverged[k],
                100 * (s.frequencyHz(k) / kBarConverged[k] - 1));
    EXPECT_LT(relativeError(s.frequencyHz(k), kBarConverged[k]), 0.01) << "mode " << k + 7;
  }
}

// Bending locks linear tets: the error falls about 4x per halving of h and stays positive.
TEST(ModalBarSlow, Tet4ConvergesFromAboveQuadratically) {
  double previous_error = 0;
  for (int layers = 1; layers <= 4; layers *= 2) {
    const double f = solveBar(layers, ElementOrder::Linear, 1).frequencyHz(0);
    const double error = f / kBarConverged[0] - 1;
    std::printf("Tet4, %d layer(s): %.1f Hz (%+.1f %%)\n", layers, f, 100 * error);
    EXPECT_GT(error, 0) << layers << " layers";
    if (layers > 1) {
      EXPECT_LT(error, previous_error / 2.5) << layers << " layers";
    }
    previous_error = error;
  }
}

}  // namespace
}  // namespace thx::audio::test_modal_bar_slow
