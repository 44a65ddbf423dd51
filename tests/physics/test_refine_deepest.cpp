// Sub-texel refinement of a ball with a bump map's contacts (clients/physics/relief_raster.hpp,
// refineDeepest): two neighbouring texels whose basin's bottom lies on their shared border are two
// starts for one point. The grooved board's marble (scenes/grooved_board.yaml) rests on a rounded
// groove's rim, a kink of the bilinear relief (its slope steep on one side of a texel's centre
// and level on the other); a parabola fitted once through each texel's own centre line leant off
// the kink by its own amount, and the two starts gave points 13 µm apart and 5 µm apart in depth:
// the marble was kicked at 1.4 mm/s each time they took turns (docs/physics.md).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "clients/physics/relief_raster.hpp"
#include "meshes/textured_ball_mesh.hpp"
#include "tests/physics/physics_fixtures.hpp"
#include "textures/generators.hpp"

namespace thx::phys::test::test_refine_deepest {
namespace {

tex::TextureMap generated(const std::string& kind, int size, std::map<std::string, double> params) {
  tex::GenerateRequest request;
  request.kind = kind;
  request.size = size;
  request.params = std::move(params);
  return tex::generate(request);
}

TEST(RefineDeepest, TwoTexelsSharingABasinsBottomOnTheirBorderGiveOnePoint) {
  // The board's U grooves (4 mm apart, 0.8 mm deep, 0.31 mm texels) and its 5 mm marble with
  // bumps 20 µm high, 2 mm apart.
  const SurfaceHolder plane = holdSurface(
      generated("grooves", 128, {{"extent", 0.04}, {"period", 0.004}, {"width", 0.004}, {"depth", 0.0008}}), 0.04, true);
  constexpr double kRadius = 0.005;
  const double tile = mesh::ballFaceArc(kRadius);
  const tex::TextureMap bumps = generated("sine", 64, {{"extent", tile}, {"amplitude", 2e-5}, {"period", 0.002}});
  FaceTexture ball;
  ball.map = &bumps;
  ball.tile_m = tile;
  const Eigen::Vector2d texel = plane.surface.mapping().texelSize(plane.surface.map());
  int pairs = 0;
  double worst_x = 0.0, worst_depth = 0.0;
  // Over a groove's floor (x = -2 mm), let down onto its rims, rolled along it a texel's length
  // in 1 µm steps (turning as it rolls).
  for (int k = 0; k < 313; ++k) {
    const double along = 1e-6 * k;
    Eigen::Isometry3d pose = at(-0.002, along, kRadius);
    pose.linear() = (Eigen::AngleAxisd(0.3 - along / kRadius, Eigen::Vector3d::UnitX()) *
                     Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitY()))
                        .toRotationMatrix();
    std::vector<ReliefCandidate> candidates;
    rasterizeRelief(plane.surface, Underside::sphere(pose, kRadius), 1e-3, candidates, &ball, nullptr, false);
    double deepest = 1.0;
    for (const ReliefCandidate& c : candidates) deepest = std::min(deepest, c.depth);
    pose.translation().z() -= deepest + 1e-6;  // its deepest texel 1 µm into the rims
    const Underside underside = Underside::sphere(pose, kRadius);
    candidates.clear();
    rasterizeRelief(plane.surface, underside, 1e-3, candidates, &ball, nullptr, false);
    std::map<std::pair<long long, long long>, const ReliefCandidate*> by_texel;
    for (const ReliefCandidate& c : candidates) by_texel[{c.i, c.j}] = &c;
    for (const ReliefCandidate& c : candidates) {
      if (c.depth > 2e-5) continue;  // where it stands on the rims, not over the floor
      const auto next = by_texel.find({c.i, c.j + 1});  // +j is -y
      if (next == by_texel.end()) continue;
      const ReliefCandidate a = refineDeepest(plane.surface, underside, c, nullptr, &ball);
      const ReliefCandidate b = refineDeepest(plane.surface, underside, *next->second, nullptr, &ball);
      // Both moved to within a hundredth of a texel of their shared border: one basin's bottom.
      const double border_y = c.p_surface.y() - 0.5 * texel.y();
      if (std::fabs(a.p_surface.y() - border_y) > 0.01 * texel.y() ||
          std::fabs(b.p_surface.y() - border_y) > 0.01 * texel.y())
        continue;
      ++pairs;
      worst_x = std::max(worst_x, std::fabs(a.p_surface.x() - b.p_surface.x()));
      worst_depth = std::max(worst_depth, std::fabs(a.depth - b.depth));
    }
  }
  std::printf("[measured] %d pairs of texels refined onto their shared border: points at most %.3g um apart along it, "
              "depths %.3g um apart\n",
              pairs, worst_x * 1e6, worst_depth * 1e6);
  ASSERT_GT(pairs, 0);
  // Fitted once through each texel's centre lines: 2.87 µm and 1.37 µm apart.
  EXPECT_LT(worst_x, 1e-8);
  EXPECT_LT(worst_depth, 1e-7);
}

}  // namespace
}  // namespace thx::phys::test::test_refine_deepest
