// The Kirchhoff plate (docs/audio.md §8.2) and Lamb's sphere (§8.3) with Tet10, on meshes
// small enough for the sanitizer tree.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "clients/audio/analysis/modal_analysis.hpp"
#include "tests/audio/modal_fixtures.hpp"

namespace thx::audio::test_modal_shapes {
namespace {

using test::relativeError;
using test::steel;

// The 12 x 12 plate resolves modes 1-7 within 1.5 % (mode 8: +3.5 %); all 8 on finer meshes in
// test_modal_shapes_slow.cpp.
TEST(ModalShapes, PlateWithinOneAndAHalfPercentOfKirchhoff) {
  test::expectPlateNearKirchhoff(12, 7);
}

// Lamb: omega a / c_s = 2.5011 (T2) and 2.6450 (S2, nu = 0.29), each 5-fold.
TEST(ModalShapes, SphereT2AndS2WithinTwoPercentWithMultiplicityFive) {
  const double a = 0.05;
  const ElasticMaterial m = steel();
  const double cs = std::sqrt(m.youngs_modulus_pa / (2 * (1 + m.poisson_ratio)) / m.density_kg_per_m3);
  ModalSettings settings;
  settings.elastic_modes = 10;
  const ModalSolution s = analyse(sphereMesh("sphere", a, 4, ElementOrder::Quadratic), m, settings);
  for (int k = 0; k < 10; ++k) {
    const double eta = s.omega_rad_per_s[k] * a / cs;
    const double ref = k < 5 ? 2.5011 : 2.6450;
    std::printf("sphere mode %d: eta %.4f (%s %.4f, %+.2f %%)\n", k + 7, eta, k < 5 ? "T2" : "S2", ref,
                100 * (eta / ref - 1));
    EXPECT_LT(relativeError(eta, ref), 0.02) << "mode " << k + 7;
  }
}

}  // namespace
}  // namespace thx::audio::test_modal_shapes
