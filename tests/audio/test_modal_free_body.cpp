// Properties every free body's modes must have, on small meshes of each structured shape:
// exactly 6 rigid modes, M-orthonormal shapes, frequencies inversely proportional to size.
#include <gtest/gtest.h>

#include <cstdio>

#include "clients/audio/analysis/fem_assembly.hpp"
#include "clients/audio/analysis/modal_analysis.hpp"
#include "tests/audio/modal_fixtures.hpp"

namespace thx::audio::test_modal_free_body {
namespace {

using test::relativeError;
using test::steel;

std::vector<TetMesh> smallMeshes() {
  return {
      boxMesh("box tet4", {0.1, 0.06, 0.04}, {5, 3, 2}, ElementOrder::Linear),
      boxMesh("box tet10", {0.1, 0.06, 0.04}, {3, 2, 1}, ElementOrder::Quadratic),
      sphereMesh("sphere tet10", 0.05, 2, ElementOrder::Quadratic),
      cylinderMesh("pen tet10", 0.005, 0.14, 1, 8, ElementOrder::Quadratic),
      slabMesh("slab tet10", 0.2, 0.2, 0.01, {4, 4, 1}, ElementOrder::Quadratic, false),
  };
}

ModalSettings fewModes() {
  ModalSettings s;
  s.elastic_modes = 8;
  return s;
}

TEST(ModalFreeBody, ExactlySixRigidModes) {
  for (const TetMesh& mesh : smallMeshes()) {
    const ModalSolution s = analyse(mesh, steel(), fewModes());
    EXPECT_EQ(s.rigid_modes, 6) << mesh.name;
    for (int k = 0; k < s.rigid_hz.size(); ++k) EXPECT_LT(std::fabs(s.rigid_hz[k]), 1.0) << mesh.name;
    // The first elastic mode is far above the rigid ones.
    EXPECT_GT(s.frequencyHz(0), 100.0) << mesh.name;
  }
}

TEST(ModalFreeBody, ShapesAreMassOrthonormal) {
  for (const TetMesh& mesh : smallMeshes()) {
    const ModalSolution s = analyse(mesh, steel(), fewModes());
    const AssembledSystem sys = assemble(mesh, steel());
    const Eigen::MatrixXd u = freeRows(s.shapes, sys.free_dof, sys.free_count);
    const Eigen::MatrixXd gram = u.transpose() * (sys.mass * u);
    EXPECT_LT((gram - Eigen::MatrixXd::Identity(gram.rows(), gram.cols())).cwiseAbs().maxCoeff(), 1e-8) << mesh.name;
    // And K-orthogonal with U^T K U = diag(omega^2).
    const Eigen::MatrixXd k = u.transpose() * (sys.stiffness * u);
    const Eigen::VectorXd w2 = s.omega_rad_per_s.array().square();
    EXPECT_LT((k - Eigen::MatrixXd(w2.asDiagonal())).cwiseAbs().maxCoeff(), 1e-7 * w2.maxCoeff()) << mesh.name;
  }
}

TEST(ModalFreeBody, ScalingTheMeshByTwoHalvesEveryFrequency) {
  for (const TetMesh& mesh : smallMeshes()) {
    const ModalSolution a = analyse(mesh, steel(), fewModes());
    const ModalSolution b = analyse(scaled(mesh, 2.0), steel(), fewModes());
    for (int k = 0; k < a.omega_rad_per_s.size(); ++k)
      EXPECT_LT(relativeError(b.omega_rad_per_s[k], 0.5 * a.omega_rad_per_s[k]), 1e-8) << mesh.name << " mode " << k;
  }
}

// CHOLMOD's supernodal Cholesky (the default) and Eigen's SimplicialLDLT factor the same K - sigma M,
// so ARPACK finds the same modes with either.
TEST(ModalFreeBody, BothFactorizationsGiveTheSameModes) {
  for (const TetMesh& mesh : smallMeshes()) {
    ModalSettings ldlt = fewModes();
    ldlt.factorization = Factorization::SimplicialLdlt;
    const ModalSolution a = analyse(mesh, steel(), fewModes());
    const ModalSolution b = analyse(mesh, steel(), ldlt);
    ASSERT_EQ(a.omega_rad_per_s.size(), b.omega_rad_per_s.size()) << mesh.name;
    for (int k = 0; k < a.omega_rad_per_s.size(); ++k)
      EXPECT_LT(relativeError(b.omega_rad_per_s[k], a.omega_rad_per_s[k]), 1e-8) << mesh.name << " mode " << k;
  }
}

// The 2-cell sphere's cubic symmetry splits Lamb's 5-fold families into pairs and triples; with
// the default Lanczos vectors every copy is found (with nev + 20 one copy of a triple was missed,
// docs/audio.md §1): elastic modes 1-8 (0-based 0-7) come as 2, 3, 3 equal values, both ways.
TEST(ModalFreeBody, EveryCopyOfARepeatedModeIsFound) {
  const TetMesh sphere = sphereMesh("sphere tet10", 0.1, 2, ElementOrder::Quadratic);
  for (Factorization f : {Factorization::CholmodSupernodal, Factorization::SimplicialLdlt}) {
    ModalSettings s = fewModes();
    s.factorization = f;
    const ModalSolution m = analyse(sphere, steel(), s);
    const auto& w = m.omega_rad_per_s;
    ASSERT_GE(w.size(), 8);
    EXPECT_LT(relativeError(w[1], w[0]), 1e-8);
    EXPECT_GT(relativeError(w[2], w[1]), 1e-3);
    EXPECT_LT(relativeError(w[4], w[2]), 1e-8);
    EXPECT_GT(relativeError(w[5], w[4]), 1e-3);
    EXPECT_LT(relativeError(w[7], w[5]), 1e-8);
  }
}

TEST(ModalFreeBody, HeldSlabHasNoRigidModesAndItsEdgesStayPut) {
  const TetMesh mesh = slabMesh("held slab", 0.2, 0.2, 0.01, {4, 4, 1}, ElementOrder::Quadratic, true);
  const ModalSolution s = analyse(mesh, steel(), fewModes());
  EXPECT_EQ(s.rigid_modes, 0);
  for (std::size_t n = 0; n < mesh.nodes.size(); ++n) {
    if (mesh.clamped[n]) {
      EXPECT_EQ(s.shapes.middleRows(Eigen::Index(3 * n), 3).cwiseAbs().maxCoeff(), 0.0);
    }
  }
  // Holding the edges stiffens the plate: its first mode lies above the free plate's.
  const ModalSolution free = analyse(slabMesh("free slab", 0.2, 0.2, 0.01, {4, 4, 1}, ElementOrder::Quadratic, false),
                                     steel(), fewModes());
  EXPECT_GT(s.frequencyHz(0), free.frequencyHz(0));
}

}  // namespace
}  // namespace thx::audio::test_modal_free_body
