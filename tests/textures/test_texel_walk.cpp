// The texel walk lists every texel a segment crosses, in order (sound needs all of them).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "textures/sampling.hpp"

namespace test_texel_walk {

using namespace thx::tex;

namespace {
bool fourNeighbours(TexelIndex a, TexelIndex b) { return std::abs(a.i - b.i) + std::abs(a.j - b.j) == 1; }
}  // namespace

TEST(TexelWalk, HorizontalSegmentListsEachColumnInOrder) {
  const TextureMap map(10, 10, Representation::Normal);
  const TexCoord a = texelCentre(map, {1, 4}), b = texelCentre(map, {7, 4});
  const auto cells = texelsOnSegment(map, a, b, Address::Clamp);
  ASSERT_EQ(cells.size(), 7u);
  for (int k = 0; k < 7; ++k) EXPECT_EQ(cells[std::size_t(k)], (TexelIndex{1 + k, 4}));
  const auto back = texelsOnSegment(map, b, a, Address::Clamp);
  ASSERT_EQ(back.size(), 7u);
  EXPECT_EQ(back.front(), (TexelIndex{7, 4}));
}

TEST(TexelWalk, CountMatchesAnalyticGridCrossings) {
  // Inside a large map nothing wraps or clamps, so a segment from cell (i0,j0) to (i1,j1) crosses
  // |i1-i0| vertical and |j1-j0| horizontal grid lines: 1 + |di| + |dj| cells, each a 4-neighbour
  // of the previous one, starting and ending in the cells containing the end points.
  const TextureMap map(1000, 1000, Representation::Normal);
  std::mt19937 rng(12345);
  std::uniform_real_distribution<double> coord(0.0, 1.0);
  for (int k = 0; k < 2000; ++k) {
    const TexCoord a{coord(rng), coord(rng)}, b{coord(rng), coord(rng)};
    const TexelIndex ta = texelOf(map, a, Address::Clamp), tb = texelOf(map, b, Address::Clamp);
    const auto cells = texelsOnSegment(map, a, b, Address::Clamp);
    ASSERT_EQ(cells.size(), std::size_t(1 + std::abs(tb.i - ta.i) + std::abs(tb.j - ta.j)));
    EXPECT_EQ(cells.front(), ta);
    EXPECT_EQ(cells.back(), tb);
    for (std::size_t c = 1; c < cells.size(); ++c) ASSERT_TRUE(fourNeighbours(cells[c - 1], cells[c]));
  }
}

TEST(TexelWalk, EveryTexelUnderTheSegmentIsListedInOrder) {
  const TextureMap map(37, 23, Representation::Normal);
  std::mt19937 rng(99);
  std::uniform_real_distribution<double> coord(0.02, 0.98);
  for (int k = 0; k < 200; ++k) {
    const TexCoord a{coord(rng), coord(rng)}, b{coord(rng), coord(rng)};
    const auto cells = texelsOnSegment(map, a, b, Address::Clamp);
    // Dense samples along the segment must visit the listed cells as an ordered subsequence
    // (sampling may skip a cell only where the segment clips a corner).
    std::size_t cursor = 0;
    for (int s = 0; s <= 20000; ++s) {
      const double t = s / 20000.0;
      const TexelIndex here = texelOf(map, {a.u + t * (b.u - a.u), a.v + t * (b.v - a.v)}, Address::Clamp);
      while (cursor < cells.size() && !(cells[cursor] == here)) ++cursor;
      ASSERT_LT(cursor, cells.size()) << "cell (" << here.i << "," << here.j << ") missing or out of order";
    }
  }
}

TEST(TexelWalk, WrapCrossesTheSeamAndFastSegmentsVisitEveryPeriod) {
  const TextureMap map(64, 64, Representation::Normal);
  const double v = texelCentre(map, {0, 10}).v;
  const auto seam = texelsOnSegment(map, texelCentre(map, {62, 10}), {1.0 + 1.5 / 64, v}, Address::Wrap);
  ASSERT_EQ(seam.size(), 4u);
  EXPECT_EQ(seam[0], (TexelIndex{62, 10}));
  EXPECT_EQ(seam[1], (TexelIndex{63, 10}));
  EXPECT_EQ(seam[2], (TexelIndex{0, 10}));
  EXPECT_EQ(seam[3], (TexelIndex{1, 10}));
  // Ten periods in one segment (a contact moving 10 texture widths in one audio frame).
  const auto fast = texelsOnSegment(map, {0.5 / 64, v}, {10.0 + 0.5 / 64, v}, Address::Wrap);
  EXPECT_EQ(fast.size(), 641u);
}

TEST(TexelWalk, ClampMergesRepeatsOutsideTheMap) {
  const TextureMap map(8, 8, Representation::Normal);
  const double v = texelCentre(map, {0, 3}).v;
  const auto cells = texelsOnSegment(map, {-3.0, v}, {0.3, v}, Address::Clamp);
  ASSERT_EQ(cells.size(), 3u);  // column 0 (all the outside part), 1, 2
  EXPECT_EQ(cells[0], (TexelIndex{0, 3}));
  EXPECT_EQ(cells[2], (TexelIndex{2, 3}));
}

TEST(TexelWalk, DegenerateAndInvalidSegments) {
  const TextureMap map(8, 8, Representation::Normal);
  const auto one = texelsOnSegment(map, {0.3, 0.3}, {0.3, 0.3}, Address::Wrap);
  ASSERT_EQ(one.size(), 1u);
  EXPECT_EQ(one[0], texelOf(map, {0.3, 0.3}, Address::Wrap));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(texelsOnSegment(map, {nan, 0.3}, {0.3, 0.3}, Address::Wrap).empty());
  // Absurd lengths stop at the bound instead of running for ever.
  EXPECT_EQ(texelsOnSegment(map, {0.0, 0.5}, {1e9, 0.5}, Address::Wrap, 1000).size(), 1000u);
  // The visitor can stop the walk.
  int seen = 0;
  walkTexels(map, {0.0, 0.5}, {1.0, 0.5}, Address::Wrap, [&](TexelIndex) { return ++seen < 3; });
  EXPECT_EQ(seen, 3);
}

TEST(TexelWalk, UnwrappedCellsCarryTheirEntryParameter) {
  // From the centre of column 0 to the centre of column 10 (row 3): column k is entered where the
  // segment crosses x = k, at t = (k - 0.5) / 10; the cells are not wrapped (columns 8, 9, 10 of
  // an 8-texel map stay 8, 9, 10).
  const TextureMap map(8, 8, Representation::Normal);
  const double v = 1.0 - 3.5 / 8;
  std::vector<long long> columns;
  std::vector<double> entries;
  const std::size_t n = walkCells(map, {0.5 / 8, v}, {10.5 / 8, v}, [&](long long i, long long j, double t) {
    EXPECT_EQ(j, 3);
    columns.push_back(i);
    entries.push_back(t);
    return true;
  });
  ASSERT_EQ(n, 11u);
  for (long long k = 0; k <= 10; ++k) {
    EXPECT_EQ(columns[std::size_t(k)], k);
    EXPECT_NEAR(entries[std::size_t(k)], k == 0 ? 0.0 : (double(k) - 0.5) / 10.0, 1e-12);
  }
}

TEST(TexelWalk, UnwrappedDiagonalEntriesIncreaseAndMatchTheGridLines) {
  // Each entry parameter puts the point of the segment on the grid line it crossed.
  const TextureMap map(64, 64, Representation::Normal);
  const TexCoord a{0.1234, 0.8765}, b{-0.377, 0.0431};
  double last = -1.0;
  long long pi = 0, pj = 0;
  bool first = true;
  walkCells(map, a, b, [&](long long i, long long j, double t) {
    EXPECT_GE(t, last);
    last = t;
    if (!first) {
      const double x = (a.u + t * (b.u - a.u)) * 64, y = (1.0 - (a.v + t * (b.v - a.v))) * 64;
      if (i != pi) {
        EXPECT_NEAR(x, double(std::max(i, pi)), 1e-9);
      }
      if (j != pj) {
        EXPECT_NEAR(y, double(std::max(j, pj)), 1e-9);
      }
      EXPECT_EQ(std::abs(i - pi) + std::abs(j - pj), 1);
    }
    first = false;
    pi = i;
    pj = j;
    return true;
  });
  EXPECT_LT(pi, 0);  // went past the left edge without wrapping
}

}  // namespace test_texel_walk
