// The slope pyramid (textures/slope_pyramid.hpp): level 0 is each texel's slopes, level k their
// mean over 2^k x 2^k texels (an odd side's last texel alone), sampled bilinearly and between
// levels; a texture that wraps has no mean slope over its tile.
#include <gtest/gtest.h>

#include <cmath>

#include "textures/height_normals.hpp"
#include "textures/slope_pyramid.hpp"

namespace thx::tex::test_slope_pyramid {
namespace {

// A relief of heights h(i, j), 1 mm texels, normals by the project's central differences.
TextureMap reliefOf(int w, int h, double (*height)(int, int), Address address) {
  HeightField field;
  field.width = w;
  field.height = h;
  field.heights_m.resize(std::size_t(w) * std::size_t(h));
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) field.heights_m[std::size_t(j) * std::size_t(w) + std::size_t(i)] = height(i, j);
  ReliefFromHeightOptions o;
  o.texel_m = {1e-3, 1e-3};
  o.address = address;
  return reliefFromHeight(field, o);
}

Eigen::Vector2d slopesOf(const TextureMap& map, int i, int j) {
  const Eigen::Vector3f n = map.normal(i, j);
  return {-double(n.x()) / n.z(), -double(n.y()) / n.z()};
}

// The texel centre (i, j) of a w x h level as uv.
TexCoord centre(int i, int j, int w, int h) { return {(i + 0.5) / w, 1.0 - (j + 0.5) / h}; }

TEST(SlopePyramid, EachLevelIsTheMeanOfTheFourTexelsUnderIt) {
  const TextureMap map = reliefOf(
      8, 8, [](int i, int j) { return 1e-4 * std::sin(0.9 * i) * std::cos(0.5 * j) + 2e-5 * i * j; }, Address::Clamp);
  const SlopePyramid p(map, Address::Clamp);
  EXPECT_EQ(p.levels(), 4);  // 8, 4, 2, 1
  for (int j = 0; j < 8; ++j)
    for (int i = 0; i < 8; ++i) {
      const Eigen::Vector2d s = p.slopes(centre(i, j, 8, 8), 0.0, Address::Clamp);
      EXPECT_NEAR((s - slopesOf(map, i, j)).norm(), 0.0, 1e-6) << i << "," << j;
    }
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) {
      const Eigen::Vector2d mean = 0.25 * (slopesOf(map, 2 * i, 2 * j) + slopesOf(map, 2 * i + 1, 2 * j) +
                                           slopesOf(map, 2 * i, 2 * j + 1) + slopesOf(map, 2 * i + 1, 2 * j + 1));
      EXPECT_NEAR((p.slopes(centre(i, j, 4, 4), 1.0, Address::Clamp) - mean).norm(), 0.0, 1e-6) << i << "," << j;
    }
  // Half way between two levels: half of each.
  const TexCoord at = centre(1, 2, 4, 4);
  const Eigen::Vector2d half = 0.5 * (p.slopes(at, 1.0, Address::Clamp) + p.slopes(at, 2.0, Address::Clamp));
  EXPECT_NEAR((p.slopes(at, 1.5, Address::Clamp) - half).norm(), 0.0, 1e-12);
  // As a normal: (-slopes, 1), unit.
  const Eigen::Vector2d s = p.slopes(at, 1.5, Address::Clamp);
  EXPECT_NEAR((p.normal(at, 1.5, Address::Clamp) - Eigen::Vector3d(-s.x(), -s.y(), 1.0).normalized()).norm(), 0.0, 1e-12);
}

TEST(SlopePyramid, AWrappedTextureHasNoMeanSlopeOverItsTile) {
  const TextureMap map = reliefOf(
      64, 32, [](int i, int j) { return 3e-4 * std::sin(2 * M_PI * i / 16.0) + 2e-4 * std::cos(2 * M_PI * j / 8.0); },
      Address::Wrap);
  double largest = 0.0;
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (int j = 0; j < 32; ++j)
    for (int i = 0; i < 64; ++i) largest = std::max(largest, slopesOf(map, i, j).norm()), mean += slopesOf(map, i, j) / 2048.0;
  EXPECT_GT(largest, 0.1);  // steep texels ...
  EXPECT_LT(mean.norm(), 1e-4);  // ... whose mean is 0 but for the normals' 16-bit rounding
  // Wrapped, the pyramid removes that rounding from every texel: no mean slope at the top level.
  const SlopePyramid wrapped(map, Address::Wrap);
  EXPECT_EQ(wrapped.levels(), 7);  // 64 x 32 ... 1 x 1
  EXPECT_LT(wrapped.slopes({0.3, 0.7}, 6.0, Address::Wrap).norm(), 1e-7);
  EXPECT_NEAR((wrapped.slopes(centre(5, 3, 64, 32), 0.0, Address::Wrap) - (slopesOf(map, 5, 3) - mean)).norm(), 0.0, 1e-6);
  // Clamped, the texture is not periodic: its mean slope is what it is.
  const SlopePyramid clamped(map, Address::Clamp);
  EXPECT_NEAR((clamped.slopes({0.3, 0.7}, 6.0, Address::Clamp) - mean).norm(), 0.0, 1e-7);
  // Beyond the top level, the top level; below level 0, level 0.
  EXPECT_EQ(wrapped.slopes({0.3, 0.7}, 6.0, Address::Wrap), wrapped.slopes({0.3, 0.7}, 40.0, Address::Wrap));
  EXPECT_EQ(wrapped.slopes({0.3, 0.7}, 0.0, Address::Wrap), wrapped.slopes({0.3, 0.7}, -3.0, Address::Wrap));
}

TEST(SlopePyramid, AnOddSidesLastTexelIsAveragedAlone) {
  const TextureMap map = reliefOf(5, 3, [](int i, int j) { return 1e-4 * i * i + 5e-5 * j; }, Address::Clamp);
  const SlopePyramid p(map, Address::Clamp);
  EXPECT_EQ(p.levels(), 4);  // 5 x 3, 3 x 2, 2 x 1, 1 x 1
  // Level 1, texel (2, 1): level 0's (4, 2) alone.
  EXPECT_NEAR((p.slopes(centre(2, 1, 3, 2), 1.0, Address::Clamp) - slopesOf(map, 4, 2)).norm(), 0.0, 1e-6);
  // Level 1, texel (2, 0): level 0's (4, 0) and (4, 1).
  EXPECT_NEAR((p.slopes(centre(2, 0, 3, 2), 1.0, Address::Clamp) - 0.5 * (slopesOf(map, 4, 0) + slopesOf(map, 4, 1))).norm(),
              0.0, 1e-6);
}

}  // namespace
}  // namespace thx::tex::test_slope_pyramid
