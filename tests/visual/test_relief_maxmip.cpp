// The accelerated relief search (--search maxmip: the walk over the relief's max-mipmap) against
// the exact CPU reference (clients/visual/cpu_reference.hpp), as test_relief_reference.cpp does
// for the linear search: the fraction of pixels whose hit lands on another texel than the
// reference's and the mean intensity error in 8-bit LSB, for steep, oblique and grazing views of
// the bricks and a box step, with self-shadowing, and thin walls that a coarse linear search
// steps over. The bounds are the values measured with Mesa 22.3.6 llvmpipe plus a margin.
#include "tests/visual/visual_fixture.hpp"

namespace thx::visual::testing::test_relief_maxmip {
namespace {

constexpr ReliefSteps kMaxMip{16, 6, 0, ReliefSearch::MaxMip};
constexpr ReliefSteps kMaxMipShadows{16, 6, 8, ReliefSearch::MaxMip};

PixelStats run(const OwnedSurface& s, const View& view, double distance_m, ReliefSteps steps) {
  return reliefAgainstReference(s.surface, view, distance_m, steps);
}

void expectWithin(const PixelStats& stats, double other_texel_fraction, double mean_lsb, const char* what) {
  EXPECT_LE(stats.otherTexelFraction(), other_texel_fraction) << what;
  EXPECT_LE(stats.meanError(), mean_lsb) << what;
}

// Walls one texel thick and `max` deep on a floor, every `period` rows: rows of thin ridges
// across a grazing view (the bilinear surface makes each a tent two cells wide).
OwnedSurface thinWalls(int texels, int period, double size_m, double depth_m) {
  tex::HeightField h(texels, texels, -depth_m);
  for (int j = 0; j < texels; j += period)
    for (int i = 0; i < texels; ++i) h.at(i, j) = 0.0;
  tex::ReliefFromHeightOptions o;
  o.texel_m = Eigen::Vector2d::Constant(size_m / texels);
  o.address = tex::Address::Wrap;
  return place(tex::reliefFromHeight(h, o), size_m);
}

TEST(VisualReliefMaxMip, BricksFromThreeViews) {
  const OwnedSurface s = generated("bricks", 128, {});
  expectWithin(run(s, kSteep, 0.08, kMaxMip), 0.0005, 0.02, "steep");      // measured 0, 0.000
  expectWithin(run(s, kOblique, 0.08, kMaxMip), 0.0005, 0.02, "oblique");  // 0, 0.000
  expectWithin(run(s, kGrazing, 0.08, kMaxMip), 0.0005, 0.02, "grazing");  // 0.0001, 0.000
}

TEST(VisualReliefMaxMip, BricksWithSelfShadowing) {
  const OwnedSurface s = generated("bricks", 128, {});
  // measured 0 / 0.014 and 0.0001 / 0.015: a pixel whose light ray grazes a brick edge
  expectWithin(run(s, kOblique, 0.08, kMaxMipShadows), 0.0005, 0.1, "oblique, shadows");
  expectWithin(run(s, kGrazing, 0.08, kMaxMipShadows), 0.0005, 0.1, "grazing, shadows");
}

TEST(VisualReliefMaxMip, BoxStepFromThreeViews) {
  const OwnedSurface s = boxStep(64, 24, 0.05, 0.001);
  expectWithin(run(s, kSteep, 0.06, kMaxMip), 0.0005, 0.02, "steep");                   // measured 0, 0
  expectWithin(run(s, kOblique, 0.06, kMaxMip), 0.0005, 0.02, "oblique");               // 0, 0.000
  expectWithin(run(s, kGrazing, 0.06, kMaxMipShadows), 0.0005, 0.1, "grazing, shadows");  // 0, 0
}

TEST(VisualReliefMaxMip, ThinWallsAreNeverSteppedOver) {
  // 0.2 mm texels, 1 mm deep: at 15 degrees 8 linear steps move 0.7 mm sideways each, more than
  // a wall's tent (0.4 mm), so the linear search runs through walls; the walk cannot.
  const OwnedSurface s = thinWalls(128, 8, 0.025, 0.001);
  const PixelStats linear = run(s, kGrazing, 0.03, {8, 6, 0});
  const PixelStats maxmip = run(s, kGrazing, 0.03, kMaxMip);
  EXPECT_GT(linear.otherTexelFraction(), 0.1) << "the case must defeat the linear search";  // 0.714
  expectWithin(maxmip, 0.001, 0.02, "thin walls, grazing");                                   // 0.0002, 0
  expectWithin(run(s, kOblique, 0.03, kMaxMipShadows), 0.0005, 0.1, "thin walls, oblique, shadows");  // 0, 0
}

TEST(VisualReliefMaxMip, ClampedBricksAtTheBorder) {
  // Clamped sampling: the walk's border ring (max_mipmap.hpp) where rays leave the map.
  OwnedSurface s = generated("bricks", 128, {});
  s.surface = tex::TexturedSurface(*s.map, s.surface.mapping(), {tex::Filter::Bilinear, tex::Address::Clamp}, true);
  RenderSettings settings = referenceLighting(SurfaceMode::Relief);
  settings.steps = kMaxMipShadows;
  CameraPlacement camera;
  camera.elevation_deg = 25;
  camera.azimuth_deg = 90;  // looking towards -y, at the map's lower edge
  camera.distance_m = 0.06;
  camera.target_local = {0.0, -0.09};
  const PixelStats stats = compareWithReference(s.surface, settings, camera);
  std::printf("maxmip clamped border: %5d px, other texel %.4f, mean %.3f LSB\n", stats.compared,
              stats.otherTexelFraction(), stats.meanError());
  EXPECT_GT(stats.compared, kImageSide * kImageSide / 8);
  expectWithin(stats, 0.0005, 0.1, "clamped, at the border");
}

}  // namespace
}  // namespace thx::visual::testing::test_relief_maxmip
