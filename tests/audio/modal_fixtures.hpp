#pragma once
// Shared by the modal tests: the reference cases of docs/audio.md §8.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "clients/audio/analysis/elastic_material.hpp"
#include "clients/audio/analysis/modal_analysis.hpp"
#include "scenes/materials.hpp"

namespace thx::audio::test {

inline ElasticMaterial steel() { return *scene::findMaterial("steel"); }

// |a / b - 1|
inline double relativeError(double a, double b) { return std::fabs(a / b - 1.0); }

// The free-free steel bar of docs/audio.md §8.1: 0.30 x 0.02 x 0.01 m, and its converged 3D elastic
// modes 7-12 (quadratic tets, unchanged between 2 and 3 layers), Hz.
inline const Eigen::Vector3d kBar(0.30, 0.02, 0.01);
inline constexpr double kBarConverged[6] = {574.3, 1135.2, 1572.0, 3044.7, 3051.2, 3887.6};

// `layers` elements through the 1 cm thickness, cells as near cubes as the bar allows.
inline ModalSolution solveBar(int layers, ElementOrder order, int modes) {
  ModalSettings settings;
  settings.elastic_modes = modes;
  return analyse(boxMesh("bar", kBar, {30 * layers, 2 * layers, layers}, order), steel(), settings);
}

// Free-free steel plate 0.3 x 0.3 x 0.005 m (docs/audio.md §8.2), Tet10 cells x cells x 1: its
// first `modes` elastic modes within 1.5 % of Kirchhoff (Leissa's lambda for nu = 0.29, modes 1-8).
inline void expectPlateNearKirchhoff(int cells, int modes) {
  constexpr double kLambda[8] = {13.557, 19.706, 24.221, 34.967, 34.967, 61.137, 61.137, 63.959};
  const double a = 0.3, h = 0.005;
  const ElasticMaterial m = steel();
  const double d = m.youngs_modulus_pa * h * h * h / (12 * (1 - m.poisson_ratio * m.poisson_ratio));
  ModalSettings settings;
  settings.elastic_modes = modes;
  const ModalSolution s =
      analyse(slabMesh("plate", a, a, h, {cells, cells, 1}, ElementOrder::Quadratic, false), m, settings);
  for (int k = 0; k < modes; ++k) {
    const double ref = kLambda[k] / (2 * std::numbers::pi * a * a) * std::sqrt(d / (m.density_kg_per_m3 * h));
    std::printf("plate %dx%d mode %d: %.1f Hz (Kirchhoff %.1f, %+.2f %%)\n", cells, cells, k + 1, s.frequencyHz(k), ref,
                100 * (s.frequencyHz(k) / ref - 1));
    EXPECT_LT(relativeError(s.frequencyHz(k), ref), 0.015) << "mode " << k + 1;
  }
}

}  // namespace thx::audio::test
