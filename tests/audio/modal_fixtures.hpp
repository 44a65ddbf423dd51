#pragma once
// Shared by the modal tests: materials of the reference cases (sound-anchors.md §2, §3).
#include <gtest/gtest.h>

#include <cmath>

#include "clients/audio/elastic_material.hpp"
#include "clients/audio/modal_analysis.hpp"
#include "scenes/materials.hpp"

namespace thx::audio::test {

inline ElasticMaterial steel() { return fromSceneMaterial(*scene::findMaterial("steel")); }

// |a / b - 1|
inline double relativeError(double a, double b) { return std::fabs(a / b - 1.0); }

// The free-free steel bar of §3a: 0.30 x 0.02 x 0.01 m, and its converged 3D elastic modes 7-12
// (quadratic tets, unchanged between 2 and 3 layers), Hz.
inline const Eigen::Vector3d kBar(0.30, 0.02, 0.01);
inline constexpr double kBarConverged[6] = {574.3, 1135.2, 1572.0, 3044.7, 3051.2, 3887.6};

// `layers` elements through the 1 cm thickness, cells as near cubes as the bar allows.
inline ModalSolution solveBar(int layers, ElementOrder order, int modes) {
  ModalSettings settings;
  settings.elastic_modes = modes;
  return analyse(boxMesh("bar", kBar, {30 * layers, 2 * layers, layers}, order), steel(), settings);
}

}  // namespace thx::audio::test
