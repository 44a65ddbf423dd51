// ModalBody::gainsAt: a mode's gain at any point of a body is its shape interpolated with the
// element's own shape functions, dotted with the direction (docs/audio.md §9).
#include <gtest/gtest.h>

#include <random>

#include "clients/audio/analysis/modal_body.hpp"
#include "tests/audio/modal_fixtures.hpp"

namespace test_modal_body {

namespace {

using namespace thx::audio;

// Fake "modes" whose shapes are a known field of position, to check the interpolation itself:
// mode 0 = a linear field, mode 1 = a quadratic one (exact for Tet10 only).
Eigen::Vector3d linearField(const Eigen::Vector3d& x) { return {1 + 2 * x.x() - x.y(), 0.5 * x.z() - 3 * x.x(), 4 * x.y() + x.z()}; }
Eigen::Vector3d quadraticField(const Eigen::Vector3d& x) {
  return {x.x() * x.y(), x.z() * x.z() - x.x(), x.y() * x.y() + 2 * x.x() * x.z()};
}

ModalBody fieldBody(ElementOrder order) {
  TetMesh mesh = boxMesh("box", {0.04, 0.03, 0.02}, {2, 2, 1}, order);
  AudibleModes m;
  m.frequency_hz = {1000, 2000};
  m.decay_per_s = {1, 1};
  m.damping_ratio = {0, 0};
  m.members = {1, 1};
  m.shapes.resize(mesh.dofCount(), 2);
  for (std::size_t n = 0; n < mesh.nodes.size(); ++n) {
    const Eigen::Vector3d x = mesh.nodes[n] * 50.0;  // O(1) values
    m.shapes.block<3, 1>(Eigen::Index(3 * n), 0) = linearField(x);
    m.shapes.block<3, 1>(Eigen::Index(3 * n), 1) = quadraticField(x);
  }
  return ModalBody(std::move(mesh), std::move(m));
}

TEST(ModalBody, InterpolatesLinearFieldsExactlyAndQuadraticOnesWithTet10) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> ux(-0.02, 0.02), uy(-0.015, 0.015), uz(-0.01, 0.01), ud(-1, 1);
  for (ElementOrder order : {ElementOrder::Linear, ElementOrder::Quadratic}) {
    const ModalBody body = fieldBody(order);
    for (int k = 0; k < 200; ++k) {
      const Eigen::Vector3d p(ux(rng), uy(rng), uz(rng)), d(ud(rng), ud(rng), ud(rng));
      const std::vector<double> g = body.gainsAt(p, d);
      ASSERT_EQ(g.size(), 2u);
      EXPECT_TRUE(body.locate(p).inside);
      EXPECT_NEAR(g[0], linearField(p * 50.0).dot(d), 1e-12) << "order " << int(order);
      if (order == ElementOrder::Quadratic) {
        EXPECT_NEAR(g[1], quadraticField(p * 50.0).dot(d), 1e-12);
      }
    }
  }
}

// A point outside the box is taken at the box's nearest point (each coordinate clamped to the
// box): the gain there is the field's, whichever boundary face the search lands on, for points
// off a face, an edge or a corner. (locate searches the boundary faces only, pruned by their boxes.)
TEST(ModalBody, OutsideTheMeshTheGainIsTheNearestPointsOnTheBoundary) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> ux(-0.05, 0.05), uy(-0.04, 0.04), uz(-0.03, 0.03), ud(-1, 1);
  const Eigen::Vector3d half(0.02, 0.015, 0.01);
  int outside = 0;
  for (ElementOrder order : {ElementOrder::Linear, ElementOrder::Quadratic}) {
    const ModalBody body = fieldBody(order);
    for (int k = 0; k < 300; ++k) {
      const Eigen::Vector3d p(ux(rng), uy(rng), uz(rng)), d(ud(rng), ud(rng), ud(rng));
      const Eigen::Vector3d nearest = p.cwiseMax(-half).cwiseMin(half);
      const bool is_outside = (nearest - p).squaredNorm() > 0.0;
      outside += is_outside;
      EXPECT_EQ(body.locate(p).inside, !is_outside) << p.transpose();
      const std::vector<double> g = body.gainsAt(p, d);
      EXPECT_NEAR(g[0], linearField(nearest * 50.0).dot(d), 1e-12) << "order " << int(order) << " at " << p.transpose();
      if (order == ElementOrder::Quadratic) {
        EXPECT_NEAR(g[1], quadraticField(nearest * 50.0).dot(d), 1e-12);
      }
    }
  }
  EXPECT_GT(outside, 300);  // most of the draws: off faces, edges and corners
}

TEST(ModalBody, AtANodeTheGainIsTheNodesShape) {
  TetMesh mesh = slabMesh("slab", 0.2, 0.2, 0.01, {3, 3, 1}, ElementOrder::Quadratic, false);
  ModalSettings s;
  s.elastic_modes = 8;
  const ElasticMaterial steel = thx::audio::test::steel();
  const AudibleModes modes = audibleModes(analyse(mesh, steel, s), steel, AudibleOptions{});
  ASSERT_GT(modes.size(), 3u);
  const ModalBody body(mesh, modes);
  for (std::size_t n = 0; n < mesh.nodes.size(); n += 7) {  // corners and edge midpoints alike
    const std::vector<double> g = body.gainsAt(mesh.nodes[n], {0.0, 0.0, 2.0});
    for (std::size_t i = 0; i < modes.size(); ++i)
      EXPECT_NEAR(g[i], 2.0 * modes.shapes(Eigen::Index(3 * n + 2), Eigen::Index(i)), 1e-9) << "node " << n << " mode " << i;
  }
  // Linear in the direction; a point just above the top face counts as on it.
  const Eigen::Vector3d p(0.031, -0.047, 0.0);
  const std::vector<double> gz = body.gainsAt(p, {0, 0, 1}), gx = body.gainsAt(p, {1, 0, 0}),
                            gsum = body.gainsAt(p, {3, 0, -2}), above = body.gainsAt(p + Eigen::Vector3d(0, 0, 1e-4), {0, 0, 1});
  EXPECT_FALSE(body.locate(p + Eigen::Vector3d(0, 0, 1e-4)).inside);
  for (std::size_t i = 0; i < modes.size(); ++i) {
    EXPECT_NEAR(gsum[i], 3 * gx[i] - 2 * gz[i], 1e-9);
    EXPECT_NEAR(above[i], gz[i], 1e-9);
  }
}

}  // namespace

}  // namespace test_modal_body
