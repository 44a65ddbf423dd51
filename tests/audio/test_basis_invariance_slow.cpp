// The shipped pen (Tet10 2 x 2 x 24, 20 modes) solved with CHOLMOD's supernodal Cholesky and with
// Eigen's LDL^T (modal-analyze --factorization) returns each bending pair in another basis; struck
// at its tip and along its side it gives the same WAV from both (docs/audio.md §9a). Label `slow`:
// two solves of the full pen take ~15 s in the sanitizer tree; test_basis_invariance.cpp has the
// short pen.
#include <gtest/gtest.h>

#include <string>

#include "clients/audio/analysis/scene_bodies.hpp"
#include "scenes/scene_loader.hpp"
#include "tests/audio/basis_fixtures.hpp"

namespace thx::audio::test_basis_invariance_slow {
namespace {

TEST(BasisInvarianceSlow, ThePenSoundsTheSameFromCholmodAndLdltSolves) {
  const SceneBody pen = penBody(scene::loadScene(std::string(THX_SOURCE_DIR) + "/scenes/default.yaml"));
  const test::FactorizationComparison c =
      test::compareFactorizations(pen.mesh, pen.material, pen.mesh.nodes[std::size_t(penTipNode(pen.mesh))], 20, "pen");
  EXPECT_LT(c.listened, 1e-6);
}

}  // namespace
}  // namespace thx::audio::test_basis_invariance_slow
