// TexturedSurface beyond a clamped border: a normal map's virtual slope continues, a relief is
// flat there (edge depth, the plane's normal), both for the interpolated reading (at) and for
// texel centres (texelPoint), which the physics relief collision reads. And a map laid at another
// size than its normals were made for (setNormalsMadeFor): its slopes follow the size it is laid at.
#include <gtest/gtest.h>

#include "textures/textured_surface.hpp"

namespace test_textured_surface {

using namespace thx::tex;

namespace {

const Eigen::Vector3f kTilted(0.3f, 0.1f, 0.95f);

TextureMap tiltedRelief(Representation r) {
  TextureMap map(4, 4, r, 0.002);
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) {
      map.setNormal(i, j, kTilted);
      if (r == Representation::Relief) map.setDepthCode(i, j, std::uint16_t(1000 * (i + 1)));
    }
  return map;
}

TexturedSurface surfaceOf(const TextureMap& map, Address address, bool relief) {
  PlaneMapping mapping;
  mapping.size_m = {0.04, 0.04};  // 1 cm texels, centred: the map spans x in [-0.02, 0.02]
  return TexturedSurface(map, mapping, SampleOptions{Filter::Bilinear, address}, relief);
}

}  // namespace

TEST(TexturedSurface, ClampedReliefIsFlatBeyondItsBorder) {
  const TextureMap map = tiltedRelief(Representation::Relief);
  const TexturedSurface s = surfaceOf(map, Address::Clamp, true);
  const Eigen::Vector3d tilted = kTilted.cast<double>().normalized();
  // Inside: the texel's normal; outside: the plane's, at the edge texel's depth.
  EXPECT_TRUE(s.at(0.015, 0.0).n_local.isApprox(tilted, 1e-4));
  const SurfacePoint out = s.at(0.05, 0.0);
  EXPECT_EQ(out.n_local, Eigen::Vector3d::UnitZ());
  EXPECT_NEAR(out.height_m, -double(map.depth(3, 1)), 1e-9);
  EXPECT_TRUE(s.texelPoint(3, 1).n_local.isApprox(tilted, 1e-4));
  const TexelPoint beyond = s.texelPoint(5, 1);
  EXPECT_EQ(beyond.n_local, Eigen::Vector3d::UnitZ());
  EXPECT_NEAR(beyond.q_local.z(), -double(map.depth(3, 1)), 1e-9);
  EXPECT_NEAR(beyond.q_local.x(), 0.035, 1e-12);  // the unwrapped centre, not the edge texel's
  EXPECT_EQ(s.texelPoint(-1, 1).n_local, Eigen::Vector3d::UnitZ());
  EXPECT_EQ(s.texelPoint(1, 4).n_local, Eigen::Vector3d::UnitZ());
}

TEST(TexturedSurface, ClampedNormalMapContinuesItsEdgeNormals) {
  for (Representation r : {Representation::Normal, Representation::Relief}) {
    const TextureMap map = tiltedRelief(r);
    const TexturedSurface s = surfaceOf(map, Address::Clamp, false);  // read as a normal map
    const Eigen::Vector3d tilted = kTilted.cast<double>().normalized();
    EXPECT_TRUE(s.at(0.05, 0.0).n_local.isApprox(tilted, 1e-4));
    EXPECT_EQ(s.at(0.05, 0.0).height_m, 0.0);
    EXPECT_TRUE(s.texelPoint(5, 1).n_local.isApprox(tilted, 1e-4));
  }
}

TEST(TexturedSurface, WrappedReliefRepeatsItsNormalsEverywhere) {
  const TextureMap map = tiltedRelief(Representation::Relief);
  const TexturedSurface s = surfaceOf(map, Address::Wrap, true);
  const Eigen::Vector3d tilted = kTilted.cast<double>().normalized();
  EXPECT_TRUE(s.at(0.05, 0.0).n_local.isApprox(tilted, 1e-4));
  EXPECT_TRUE(s.texelPoint(5, 1).n_local.isApprox(tilted, 1e-4));
  EXPECT_NEAR(s.texelPoint(5, 1).q_local.z(), -double(map.depth(1, 1)), 1e-9);
}

// Laid at 0.04 m but made for 0.08 m along x and 0.02 m along y: the slopes double along x and
// halve along y, the depth stays; without the call, or with a zero size, the map's normals.
TEST(TexturedSurface, NormalsFollowTheSizeTheMapIsLaidAt) {
  const TextureMap map = tiltedRelief(Representation::Relief);
  TexturedSurface s = surfaceOf(map, Address::Wrap, true);
  const SurfacePoint before = s.at(0.005, 0.003);
  s.setNormalsMadeFor({0.08, 0.02});
  const SurfacePoint after = s.at(0.005, 0.003);
  const Eigen::Vector3d expected = Eigen::Vector3d(0.3 * 2.0, 0.1 * 0.5, 0.95).normalized();
  EXPECT_TRUE(after.n_local.isApprox(expected, 1e-4)) << after.n_local.transpose();  // the map stores its normals quantised
  EXPECT_EQ(after.height_m, before.height_m);
  EXPECT_TRUE(s.texelPoint(1, 2).n_local.isApprox(expected, 1e-4));
  s.setNormalsMadeFor({0.0, 0.0});
  EXPECT_TRUE(s.at(0.005, 0.003).n_local.isApprox(before.n_local, 1e-12));
}

}  // namespace test_textured_surface
