// The relief's max-mipmap (clients/visual/max_mipmap.hpp) on the CPU: level 0 holds each cell's
// corner depths exactly as the library's sampler sees them (wrap, clamp with its ring of border
// cells, nearest); every coarser box is the minimum of its children; and no point of the surface
// in a box lies above the box's bound (the property that lets the search skip it).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "clients/visual/max_mipmap.hpp"

namespace thx::visual::test_max_mipmap {
namespace {

tex::TextureMap randomRelief(int w, int h, unsigned seed) {
  tex::TextureMap map(w, h, tex::Representation::Relief, 0.002);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> depth(0.0, 0.002);
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) map.setDepth(i, j, depth(rng));
  return map;
}

float corner(const MaxMipmap& m, int i, int j, int c) { return m.levels[0].depths[(std::size_t(j) * m.levels[0].width + i) * 4 + c]; }

// The library's own bilinear depth at continuous centre-grid coordinates (s, t).
double bilinear(const tex::TextureMap& map, tex::Address address, double s, double t) {
  const int i = int(std::floor(s)), j = int(std::floor(t));
  const double fx = s - i, fy = t - j;
  const auto d = [&](int a, int b) {
    return double(map.depth(tex::resolveIndex(a, map.width(), address), tex::resolveIndex(b, map.height(), address)));
  };
  return (1 - fy) * ((1 - fx) * d(i, j) + fx * d(i + 1, j)) + fy * ((1 - fx) * d(i, j + 1) + fx * d(i + 1, j + 1));
}

void expectCoarseLevelsAreMinima(const MaxMipmap& m) {
  for (int level = 1; level <= m.topLevel(); ++level) {
    const MaxMipmapLevel& fine = m.levels[std::size_t(level - 1)];
    const MaxMipmapLevel& coarse = m.levels[std::size_t(level)];
    EXPECT_EQ(coarse.width, std::max(1, fine.width / 2));
    EXPECT_EQ(coarse.height, std::max(1, fine.height / 2));
    for (int j = 0; j < coarse.height; ++j)
      for (int i = 0; i < coarse.width; ++i) {
        float expected = INFINITY;
        for (int dj = 0; dj < 2; ++dj)
          for (int di = 0; di < 2; ++di)
            if (2 * i + di < fine.width && 2 * j + dj < fine.height)
              expected = std::min(expected, fine.bound(2 * i + di, 2 * j + dj));
        ASSERT_EQ(coarse.bound(i, j), expected) << "level " << level << " box " << i << "," << j;
      }
  }
}

// Every sampled point of the surface lies at or below the bound of each box holding it.
void expectConservative(const MaxMipmap& m, const tex::TextureMap& map, tex::Address address, double s_lo, double s_hi) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> coord(s_lo, s_hi);
  for (int n = 0; n < 4000; ++n) {
    const double s = coord(rng), t = coord(rng) * map.height() / map.width();
    const double depth = bilinear(map, address, s, t);
    const double ms = s + m.offset, mt = t + m.offset;
    for (int level = 0; level <= m.topLevel(); ++level) {
      const MaxMipmapLevel& l = m.levels[std::size_t(level)];
      const int size = 1 << level;
      int ki = int(std::floor(ms / size)), kj = int(std::floor(mt / size));
      if (m.wrap) {
        const int nx = m.cells_x >> level, ny = m.cells_y >> level;
        ki = ((ki % nx) + nx) % nx, kj = ((kj % ny) + ny) % ny;
      } else {
        ki = std::clamp(ki, 0, ((m.cells_x + size - 1) >> level) - 1);
        kj = std::clamp(kj, 0, ((m.cells_y + size - 1) >> level) - 1);
      }
      ASSERT_LE(l.bound(ki, kj), depth + 1e-9) << "level " << level << " at s " << s << " t " << t;
    }
  }
}

TEST(VisualMaxMipmap, WrappedBilinearCornersAndLevels) {
  const tex::TextureMap map = randomRelief(64, 32, 1);
  const MaxMipmap m = buildMaxMipmap(map, {tex::Filter::Bilinear, tex::Address::Wrap});
  EXPECT_EQ(m.offset, 0);
  EXPECT_EQ(m.cells_x, 64);
  EXPECT_EQ(m.topLevel(), 5);  // 2 x 1 boxes: whole periods
  // The last cell closes the period: corners (63, 0) and (0, 0).
  EXPECT_EQ(corner(m, 63, 5, 0), map.depth(63, 5));
  EXPECT_EQ(corner(m, 63, 5, 1), map.depth(0, 5));
  EXPECT_EQ(corner(m, 63, 31, 3), map.depth(0, 0));
  expectCoarseLevelsAreMinima(m);
  expectConservative(m, map, tex::Address::Wrap, -100.0, 200.0);
}

TEST(VisualMaxMipmap, WrappedSidesNotPowersOfTwoStopAtWholePeriods) {
  const tex::TextureMap map = randomRelief(24, 24, 2);
  const MaxMipmap m = buildMaxMipmap(map, {tex::Filter::Bilinear, tex::Address::Wrap});
  EXPECT_EQ(m.topLevel(), 3);  // 24 = 3 x 8
  EXPECT_EQ(m.levels.back().width, 3);
  expectCoarseLevelsAreMinima(m);
  expectConservative(m, map, tex::Address::Wrap, -50.0, 80.0);
}

TEST(VisualMaxMipmap, ClampedBilinearHasARingOfBorderCells) {
  const tex::TextureMap map = randomRelief(20, 20, 3);
  const MaxMipmap m = buildMaxMipmap(map, {tex::Filter::Bilinear, tex::Address::Clamp});
  EXPECT_EQ(m.offset, 1);
  EXPECT_EQ(m.cells_x, 21);
  EXPECT_EQ(m.levels[0].width, 32);  // padded to a power of two
  EXPECT_EQ(m.topLevel(), 5);
  // Stored cell 0 lies between the map's border and the first centre: both corners are texel 0.
  EXPECT_EQ(corner(m, 0, 4, 0), map.depth(0, 3));
  EXPECT_EQ(corner(m, 0, 4, 1), map.depth(0, 3));
  EXPECT_EQ(corner(m, 0, 4, 3), map.depth(0, 4));
  EXPECT_TRUE(std::isinf(m.levels[0].bound(25, 3))) << "padding never bounds anything";
  expectCoarseLevelsAreMinima(m);
  expectConservative(m, map, tex::Address::Clamp, -30.0, 50.0);  // far beyond the map, too
}

TEST(VisualMaxMipmap, NearestCellsAreTexels) {
  const tex::TextureMap map = randomRelief(16, 16, 4);
  const MaxMipmap m = buildMaxMipmap(map, {tex::Filter::Nearest, tex::Address::Wrap});
  EXPECT_FALSE(m.between_centres);
  for (int c = 0; c < 4; ++c) EXPECT_EQ(corner(m, 7, 9, c), map.depth(7, 9));
  EXPECT_EQ(m.levels.back().bound(0, 0), *std::min_element(m.levels[0].depths.begin(), m.levels[0].depths.end()));
}

}  // namespace
}  // namespace thx::visual::test_max_mipmap
