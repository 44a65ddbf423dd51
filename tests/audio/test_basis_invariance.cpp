// The sound does not depend on the basis the eigensolver returns inside a repeated mode's
// subspace (docs/audio.md §9a): every mode is heard through the body's listener w
// (observation.hpp) and a merge sums contributions, not shapes. The shipped pen (Tet10 2 x 2 x 24)
// is in test_basis_invariance_slow.cpp; here a short one (2 x 2 x 6) keeps the sanitizer run fast.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "clients/audio/analysis/modal_error.hpp"
#include "clients/audio/analysis/observation.hpp"
#include "clients/audio/analysis/scene_bodies.hpp"
#include "scenes/scene_loader.hpp"
#include "tests/audio/basis_fixtures.hpp"
#include "tests/audio/modal_fixtures.hpp"

namespace thx::audio::test_basis_invariance {
namespace {

using namespace test;

// A short steel pen: its square cross-section gives equal bending pairs.
const TetMesh& shortPenMesh() {
  static const TetMesh m = cylinderMesh("pen", 0.005, 0.12, 2, 6, ElementOrder::Quadratic);
  return m;
}
const ModalSolution& shortPen() {
  static const ModalSolution s = [] {
    ModalSettings ms;
    ms.elastic_modes = 12;
    return analyse(shortPenMesh(), steel(), ms);
  }();
  return s;
}
const TetMesh& sphereMeshOnce() {
  static const TetMesh m = sphereMesh("sphere", 0.1, 4, ElementOrder::Quadratic);
  return m;
}
// A steel ball: T2 and S2, each split by the cube-mapped mesh into 2 + 3 exact copies.
const ModalSolution& sphere() {
  static const ModalSolution s = [] {
    ModalSettings ms;
    ms.elastic_modes = 10;
    return analyse(sphereMeshOnce(), steel(), ms);
  }();
  return s;
}
const TetMesh& shippedPenMesh() {
  static const TetMesh m = penBody(scene::loadScene(std::string(THX_SOURCE_DIR) + "/scenes/default.yaml")).mesh;
  return m;
}

TEST(BasisInvariance, RotatingThePensBendingPairsLeavesTheSoundUnchanged) {
  const ModalSolution& s = shortPen();
  const std::vector<std::vector<int>> sets = repeatedSets(s);
  ASSERT_GE(sets.size(), 2u);  // bending pairs in x and y
  for (const auto& set : sets) EXPECT_EQ(set.size(), 2u);
  const ModalSolution r = rotated(s, sets, 7);
  EXPECT_GT(basisChange(s, r), 0.1);
  for (bool merge : {true, false}) expectSameSound(shortPenMesh(), steel(), s, r, merge, "short pen");
}

TEST(BasisInvariance, RotatingTheSpheresRepeatedModesLeavesTheSoundUnchanged) {
  const ModalSolution& s = sphere();
  const std::vector<std::vector<int>> sets = repeatedSets(s);
  ASSERT_EQ(sets.size(), 4u);
  const ModalSolution r = rotated(s, sets, 11);
  EXPECT_GT(basisChange(s, r), 0.1);
  for (bool merge : {true, false}) expectSameSound(sphereMeshOnce(), steel(), s, r, merge, "sphere, 2 + 3 copies");
}

// Merging sums the members' contributions, so a merged mode is the same for any orthonormal basis
// of the members' span, even one mixing modes of different frequencies (not an eigenbasis).
TEST(BasisInvariance, AMergedQuintupletIsTheSameInAnyBasisOfItsSpan) {
  const ModalSolution& s = sphere();
  const ModalSolution r = rotated(s, {{0, 1, 2, 3, 4}, {5, 6, 7, 8, 9}}, 19);
  EXPECT_GT(basisChange(s, r), 0.1);
  expectSameSound(sphereMeshOnce(), steel(), s, r, true, "sphere, each quintuplet rotated as a whole");
}

TEST(BasisInvariance, AModesSignDoesNotChangeTheSound) {
  ModalSolution r = shortPen();
  for (int k = 0; k < r.omega_rad_per_s.size(); k += 3) r.shapes.col(k) *= -1.0, r.observation[k] *= -1.0;
  for (bool merge : {true, false}) expectSameSound(shortPenMesh(), steel(), shortPen(), r, merge, "short pen, signs");
}

// CHOLMOD and LDL^T return the short pen's bending pairs in other bases; its WAVs agree.
TEST(BasisInvariance, AShortPenSoundsTheSameFromCholmodAndLdltSolves) {
  const TetMesh& m = shortPenMesh();
  const FactorizationComparison c =
      compareFactorizations(m, steel(), m.nodes[std::size_t(penTipNode(m))], 12, "short_pen");
  EXPECT_LT(c.listened, 1e-6);
}

// The observation functional on a hand-checked mesh: a 4 x 4 x 4-cell box has nodes at multiples
// of 0.5 of its half extents, so the targets of kPickupTargets pick the face-interior nodes
// (0.5, 0.5, 1), (-0.5, 0.5, -1), (1, -0.5, 0) and (0, -1, -0.5), whose normals are the faces'.
TEST(Observation, BoxPickupsAreTheNearestSurfaceNodesWithTheirFacesNormals) {
  const Eigen::Vector3d half(0.2, 0.15, 0.1);
  const TetMesh mesh = boxMesh("box", 2 * half, {4, 4, 4}, ElementOrder::Linear);
  const Eigen::Vector3d at[4] = {{0.5, 0.5, 1}, {-0.5, 0.5, -1}, {1, -0.5, 0}, {0, -1, -0.5}};
  const Eigen::Vector3d normal[4] = {{0, 0, 1}, {0, 0, -1}, {1, 0, 0}, {0, -1, 0}};
  const std::vector<Pickup> ps = pickups(mesh);
  ASSERT_EQ(ps.size(), 4u);
  Eigen::VectorXd expected = Eigen::VectorXd::Zero(mesh.dofCount());
  for (int k = 0; k < 4; ++k) {
    EXPECT_LT((mesh.nodes[std::size_t(ps[std::size_t(k)].node)] - at[k].cwiseProduct(half)).norm(), 1e-12) << k;
    EXPECT_LT((ps[std::size_t(k)].normal - normal[k]).norm(), 1e-12) << k;
    expected.segment<3>(3 * ps[std::size_t(k)].node) += 0.25 * normal[k];
  }
  // Weighted by the box's surface, 2 (0.4 x 0.3 + 0.4 x 0.2 + 0.3 x 0.2) = 0.52 m^2.
  EXPECT_NEAR(surfaceArea(mesh), 0.52, 1e-14);
  EXPECT_LT((observationVector(mesh) - 0.52 * expected).cwiseAbs().maxCoeff(), 1e-15);
}

TEST(Observation, HeldNodesAreNeverPickups) {
  const TetMesh slab = slabMesh("slab", 0.2, 0.2, 0.01, {6, 6, 1}, ElementOrder::Linear, true);
  for (const Pickup& p : pickups(slab)) {
    EXPECT_FALSE(slab.clamped[std::size_t(p.node)]);
    EXPECT_NEAR(std::fabs(p.normal.z()), 1.0, 1e-12);  // on the top or bottom face
  }
  // Targets 1 and 2 on the top and bottom faces (docs/audio.md §9a's table).
  EXPECT_NEAR(pickups(slab)[0].normal.z(), 1.0, 1e-12);
  EXPECT_NEAR(pickups(slab)[1].normal.z(), -1.0, 1e-12);
  // A slab like the shipped one (Tet10, 2 layers): targets 3 and 4 on the +x and -y sides when
  // free; held, on the free top-face nodes next to those sides.
  for (bool clamp : {false, true}) {
    const TetMesh shipped = slabMesh("slab", 0.2, 0.2, 0.01, {6, 6, 2}, ElementOrder::Quadratic, clamp);
    const std::vector<Pickup> ps = pickups(shipped);
    if (!clamp) {
      EXPECT_NEAR(ps[2].normal.x(), 1.0, 1e-12);
      EXPECT_NEAR(ps[3].normal.y(), -1.0, 1e-12);
    } else {
      EXPECT_NEAR(ps[2].normal.z(), 1.0, 1e-12);
      EXPECT_NEAR(shipped.nodes[std::size_t(ps[2].node)].x(), 0.1 - 0.2 / 12, 1e-12);
      EXPECT_NEAR(std::fabs(ps[3].normal.z()), 1.0, 1e-12);
      EXPECT_NEAR(shipped.nodes[std::size_t(ps[3].node)].y(), -0.1 + 0.2 / 12, 1e-12);
    }
  }
  TetMesh held = slab;
  std::fill(held.clamped.begin(), held.clamped.end(), char(1));
  EXPECT_THROW(pickups(held), ModalError);
}

// The shipped pen (axis z, tip at -z): targets 1 and 2 on its end faces, 3 and 4 on its side,
// 3 above the middle and 4 towards the tip.
TEST(Observation, ThePensPickupsAreOnBothEndsAndItsSide) {
  const TetMesh& mesh = shippedPenMesh();
  const std::vector<Pickup> ps = pickups(mesh);
  ASSERT_EQ(ps.size(), 4u);
  EXPECT_NEAR(ps[0].normal.z(), 1.0, 1e-9);
  EXPECT_NEAR(ps[1].normal.z(), -1.0, 1e-9);
  for (int k : {2, 3}) EXPECT_NEAR(ps[std::size_t(k)].normal.z(), 0.0, 1e-9) << k;
  EXPECT_GT(mesh.nodes[std::size_t(ps[2].node)].z(), 0.0);
  EXPECT_LT(mesh.nodes[std::size_t(ps[3].node)].z(), 0.0);
}

// Hand-made modes: each audible mode's column is u (w . u), so a strike J at a node drives it by
// (J . u)(w . u); a merged mode sums its members' such products.
TEST(Observation, AModeIsHeardAsItsDriveTimesItsObservation) {
  ModalSolution s;
  s.mesh_dofs = 6;
  s.omega_rad_per_s = Eigen::Vector3d(2 * std::numbers::pi * 1000, 2 * std::numbers::pi * 1001, 2 * std::numbers::pi * 3000);
  s.shapes.resize(6, 3);
  s.shapes.col(0) << 1, 2, 0, -1, 0.5, 3;
  s.shapes.col(1) << 0, 1, -2, 0.25, 1, 0;
  s.shapes.col(2) << 4, 0, 1, 0, -2, 1;
  s.observation = Eigen::Vector3d(0.5, -2.0, 0.1);
  ElasticMaterial m = steel();
  m.rayleigh_alpha_per_s = 0, m.rayleigh_beta_s = 0;
  const Eigen::Vector3d j(0.3, -0.7, 0.2);  // impulse at node 1 (DOFs 3..5)
  AudibleOptions o;
  o.merge = false;
  const AudibleModes single = audibleModes(s, m, o);
  ASSERT_EQ(single.size(), 3u);
  // Mode 0: J . u = 0.3 (-1) - 0.7 (0.5) + 0.2 (3) = -0.05, times w . u = 0.5.
  EXPECT_NEAR(single.shapes.row(3).col(0).value() * j.x() + single.shapes(4, 0) * j.y() + single.shapes(5, 0) * j.z(),
              -0.05 * 0.5, 1e-15);
  for (int k = 0; k < 3; ++k)
    EXPECT_LT((single.shapes.col(k) - s.shapes.col(k) * s.observation[k]).cwiseAbs().maxCoeff(), 1e-15);
  // 1000 and 1001 Hz merge (threshold 3 Hz): the column is the sum of the two products.
  const AudibleModes merged = audibleModes(s, m, AudibleOptions{});
  ASSERT_EQ(merged.size(), 2u);
  EXPECT_EQ(merged.members[0], 2);
  const Eigen::VectorXd sum = s.shapes.col(0) * 0.5 + s.shapes.col(1) * -2.0;
  EXPECT_LT((merged.shapes.col(0) - sum).cwiseAbs().maxCoeff(), 1e-15);
  // No observation values: refused, not guessed.
  s.observation.resize(0);
  EXPECT_THROW(audibleModes(s, m, o), std::logic_error);
}

}  // namespace
}  // namespace thx::audio::test_basis_invariance
