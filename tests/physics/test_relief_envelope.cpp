// A relief's upper envelope merged along one axis (clients/physics/relief_envelope.hpp): each
// level's texel the highest of its run of the map's texels, with that texel's normal; the level
// a chart squeezed along one axis reads.
#include <gtest/gtest.h>

#include <random>

#include "clients/physics/relief_envelope.hpp"

namespace {

using thx::phys::buildReliefEnvelopes;
using thx::phys::envelopeFor;
using thx::phys::ReliefEnvelopes;
using thx::tex::Representation;
using thx::tex::TextureMap;

TextureMap randomRelief(int width, int height, unsigned seed) {
  TextureMap map(width, height, Representation::Relief, 1e-3);
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> code(0, 65535);
  std::uniform_real_distribution<float> slope(-0.5f, 0.5f);
  for (int j = 0; j < height; ++j)
    for (int i = 0; i < width; ++i) {
      map.setDepthCode(i, j, std::uint16_t(code(rng)));
      map.setNormal(i, j, Eigen::Vector3f(slope(rng), slope(rng), 1.0f));
    }
  return map;
}

TEST(ReliefEnvelope, EachLevelHoldsTheHighestTexelOfItsRunWithThatTexelsNormal) {
  const TextureMap map = randomRelief(64, 32, 7);
  const ReliefEnvelopes e = buildReliefEnvelopes(map);
  ASSERT_EQ(e.along_i.size(), 5u);  // runs of 2 to 32 texels: 64 / 64 = 1 texel is below the least side
  ASSERT_EQ(e.along_j.size(), 4u);  // 32 / 32 = 1 likewise
  for (std::size_t level = 0; level < e.along_i.size(); ++level) {
    const TextureMap& m = e.along_i[level];
    const int run = 2 << level;
    ASSERT_EQ(m.width(), 64 / run);
    ASSERT_EQ(m.height(), 32);
    EXPECT_EQ(m.maxDepth(), map.maxDepth());
    for (int j = 0; j < m.height(); ++j)
      for (int i = 0; i < m.width(); ++i) {
        int highest = i * run;
        for (int k = i * run; k < (i + 1) * run; ++k)
          if (map.depthCode(k, j) < map.depthCode(highest, j)) highest = k;
        EXPECT_EQ(m.depthCode(i, j), map.depthCode(highest, j)) << level << " " << i << " " << j;
        EXPECT_EQ(m.normalCodeX(i, j), map.normalCodeX(highest, j));
        EXPECT_EQ(m.normalCodeY(i, j), map.normalCodeY(highest, j));
      }
  }
  for (std::size_t level = 0; level < e.along_j.size(); ++level) {
    const TextureMap& m = e.along_j[level];
    const int run = 2 << level;
    ASSERT_EQ(m.width(), 64);
    ASSERT_EQ(m.height(), 32 / run);
    for (int j = 0; j < m.height(); ++j)
      for (int i = 0; i < m.width(); ++i) {
        std::uint16_t least = 65535;
        for (int k = j * run; k < (j + 1) * run; ++k) least = std::min(least, map.depthCode(i, k));
        EXPECT_EQ(m.depthCode(i, j), least);
      }
  }
}

TEST(ReliefEnvelope, LevelsStopWhereARunNoLongerDividesTheSideAndANormalMapHasNone) {
  const ReliefEnvelopes e = buildReliefEnvelopes(randomRelief(40, 1024, 3));
  EXPECT_EQ(e.along_i.size(), 3u);  // runs of 2, 4 and 8 (5 texels); 16 does not divide 40
  EXPECT_EQ(e.along_j.size(), std::size_t(thx::phys::kMaxEnvelopeLevel));  // runs of up to 64
  EXPECT_TRUE(buildReliefEnvelopes(TextureMap(64, 64, Representation::Normal)).along_i.empty());
}

TEST(ReliefEnvelope, AChartSqueezedAlongOneAxisReadsTheLevelWhoseTexelsAreNoLongerThanTheOthers) {
  const TextureMap map = randomRelief(128, 128, 5);
  const ReliefEnvelopes e = buildReliefEnvelopes(map);
  // Texels 10 um along x and 312 um along y (the bowl of bricks at its floor's centre): 31 of them
  // make one, so runs of 16, whose texels are 160 um.
  EXPECT_EQ(&envelopeFor(e, map, 10e-6, 312e-6), &e.along_i[3]);
  EXPECT_EQ(&envelopeFor(e, map, -10e-6, 312e-6), &e.along_i[3]);
  EXPECT_EQ(&envelopeFor(e, map, 312e-6, 10e-6), &e.along_j[3]);
  // Less than twice: the map itself; exactly twice: runs of 2.
  EXPECT_EQ(&envelopeFor(e, map, 1e-4, 1.9e-4), &map);
  EXPECT_EQ(&envelopeFor(e, map, 1e-4, 2e-4), &e.along_i[0]);
  // Squeezed beyond the last level: the last level (the raster strides over what is left).
  EXPECT_EQ(&envelopeFor(e, map, 1e-6, 1e-3), &e.along_i.back());
}

}  // namespace
