// Relief mapping against the exact CPU reference (issue 15): the view ray against the bilinear
// depth field the haptic renderer feels (clients/visual/cpu_reference.hpp), for steep, oblique
// and grazing views of a box-shaped step and of bricks. Pinned: the fraction of pixels whose hit
// lands on another texel than the reference's, and the mean intensity error in 8-bit LSB.
// The bounds are the values measured with Mesa 22.3.6 llvmpipe plus a margin; the search is
// deterministic, so a change beyond them is a change in the shader or the reference.
#include "tests/visual/visual_fixture.hpp"

namespace thx::visual::testing::test_relief_reference {
namespace {

struct Bound {
  double other_texel_fraction;
  double mean_lsb;
};

PixelStats run(const OwnedSurface& s, const View& view, double distance_m, ReliefSteps steps) {
  return reliefAgainstReference(s.surface, view, distance_m, steps);
}

void expectWithin(const PixelStats& stats, const Bound& bound, const char* what) {
  EXPECT_LE(stats.otherTexelFraction(), bound.other_texel_fraction) << what;
  EXPECT_LE(stats.meanError(), bound.mean_lsb) << what;
}

TEST(VisualReliefReference, BoxStepFromThreeViews) {
  // 64 texels over 5 cm, a 24-texel raised square, 1 mm deep around it.
  const OwnedSurface s = boxStep(64, 24, 0.05, 0.001);
  const ReliefSteps no_shadow{16, 6, 0};
  expectWithin(run(s, kSteep, 0.06, no_shadow), {0.0005, 0.02}, "steep");      // measured 0.0001, 0.000
  expectWithin(run(s, kOblique, 0.06, no_shadow), {0.0005, 0.02}, "oblique");  // 0.0000, 0.000
  expectWithin(run(s, kGrazing, 0.06, no_shadow), {0.0005, 0.02}, "grazing");  // 0.0000, 0.001
  expectWithin(run(s, kGrazing, 0.06, {16, 6, 16}), {0.0005, 0.5}, "grazing, 16 shadow steps");
  // measured 0.184: 16 samples towards the light place the wall's shadow edge a sample off
}

TEST(VisualReliefReference, BricksFromThreeViews) {
  const OwnedSurface s = generated("bricks", 128, {});
  const ReliefSteps no_shadow{16, 6, 0};
  expectWithin(run(s, kSteep, 0.08, no_shadow), {0.0005, 0.02}, "steep");    // measured 0.0001, 0.007
  expectWithin(run(s, kOblique, 0.08, no_shadow), {0.002, 0.15}, "oblique");  // 0.0010, 0.068
  expectWithin(run(s, kGrazing, 0.08, no_shadow), {0.008, 0.4}, "grazing");   // 0.0046, 0.220
}

TEST(VisualReliefReference, SelfShadowingAgreesWithTheExactLightRay) {
  const OwnedSurface s = generated("bricks", 128, {});
  expectWithin(run(s, kOblique, 0.08, {16, 6, 8}), {0.002, 0.15}, "oblique, 8 shadow steps");   // measured 0.0010, 0.075
  expectWithin(run(s, kOblique, 0.08, {16, 6, 32}), {0.002, 0.15}, "oblique, 32 shadow steps");  // 0.0010, 0.078
}

TEST(VisualReliefReference, MoreStepsGetCloserToTheExactHit) {
  const OwnedSurface s = boxStep(64, 24, 0.05, 0.001);
  const PixelStats coarse = run(s, kGrazing, 0.06, {4, 0, 0});
  const PixelStats fine = run(s, kGrazing, 0.06, {64, 8, 0});
  EXPECT_LT(fine.otherTexelFraction(), coarse.otherTexelFraction());
  EXPECT_LT(fine.meanError(), coarse.meanError());
  expectWithin(fine, {0.0005, 0.02}, "grazing 64+8");  // measured 0, 0 (4+0: 0.0293, 0.417)
}

}  // namespace
}  // namespace thx::visual::testing::test_relief_reference
