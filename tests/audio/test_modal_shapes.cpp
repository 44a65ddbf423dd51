// The Kirchhoff plate (sound-anchors.md §3b) and Lamb's sphere (§3c) with Tet10, on meshes
// small enough for the sanitizer tree.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "clients/audio/modal_analysis.hpp"
#include "tests/audio/modal_fixtures.hpp"

namespace thx::audio {
namespace {

using test::relativeError;
using test::steel;

// Free-free square plate, Leissa's lambda for nu = 0.29 (modes 1-8).
constexpr double kPlateLambda[8] = {13.557, 19.706, 24.221, 34.967, 34.967, 61.137, 61.137, 63.959};

double kirchhoffHz(double lambda, double a, double h, const ElasticMaterial& m) {
  const double d = m.youngs_modulus_pa * h * h * h / (12 * (1 - m.poisson_ratio * m.poisson_ratio));
  return lambda / (2 * std::numbers::pi * a * a) * std::sqrt(d / (m.density_kg_per_m3 * h));
}

TEST(ModalShapes, PlateWithinOneAndAHalfPercentOfKirchhoff) {
  const double a = 0.3, h = 0.005;
  ModalSettings settings;
  settings.elastic_modes = 8;
  const ModalSolution s = analyse(slabMesh("plate", a, a, h, {16, 16, 1}, ElementOrder::Quadratic, false), steel(), settings);
  for (int k = 0; k < 8; ++k) {
    const double ref = kirchhoffHz(kPlateLambda[k], a, h, steel());
    std::printf("plate mode %d: %.1f Hz (Kirchhoff %.1f, %+.2f %%)\n", k + 1, s.frequencyHz(k), ref,
                100 * (s.frequencyHz(k) / ref - 1));
    EXPECT_LT(relativeError(s.frequencyHz(k), ref), 0.015) << "mode " << k + 1;
  }
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
}  // namespace thx::audio
