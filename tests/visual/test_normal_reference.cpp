// Normal mapping against n_s . l computed on the CPU with the textures library's own bilinear
// sampler (issue 15): one directional light, no ambient or specular, every pixel away from edges.
#include "tests/visual/visual_fixture.hpp"

namespace thx::visual::testing::test_normal_reference {
namespace {

void expectWithinOneLsb(const OwnedSurface& s, const CameraPlacement& camera) {
  const PixelStats stats = compareWithReference(s.surface, referenceLighting(SurfaceMode::Normal), camera);
  std::printf("normal mapping: %d pixels, mean %.3f LSB, max %d LSB\n", stats.compared, stats.meanError(),
              stats.max_error);
  EXPECT_GT(stats.compared, kImageSide * kImageSide / 2);
  EXPECT_LE(stats.meanError(), 1.0);
  EXPECT_LE(stats.max_error, 4);
}

TEST(VisualNormalReference, SineBumpsSeenFromAbove) {
  // 64 texels over 0.2 m; the view spans ~18 texels, so each texel covers ~7 pixels and the
  // bilinear interpolation between centres is what is being compared.
  const OwnedSurface s = generated("sine", 64, {{"amplitude", 0.002}, {"period", 0.025}});
  CameraPlacement top;
  top.elevation_deg = 90;
  top.distance_m = 0.08;
  top.target_local = {0.013, -0.007};
  expectWithinOneLsb(s, top);
}

TEST(VisualNormalReference, BricksSeenObliquely) {
  const OwnedSurface s = generated("bricks", 128, {});
  CameraPlacement oblique;
  oblique.elevation_deg = 45;
  oblique.azimuth_deg = -60;
  oblique.distance_m = 0.1;
  expectWithinOneLsb(s, oblique);
}

TEST(VisualNormalReference, SeamOfAWrappedMapIsSampledAcrossTheBorder) {
  // Looking at the map's corner region from beyond it is not possible (the quad ends there), so
  // the camera looks at the border from inside: texels at u near 0 interpolate with u near 1.
  const OwnedSurface s = generated("pebbles", 64, {});
  CameraPlacement near_edge;
  near_edge.elevation_deg = 90;
  near_edge.distance_m = 0.05;
  near_edge.target_local = {-0.085, 0.085};
  expectWithinOneLsb(s, near_edge);
}

}  // namespace
}  // namespace thx::visual::testing::test_normal_reference
