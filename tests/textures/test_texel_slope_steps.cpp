// The slope steps a servo reads instead of a texel's neighbourhood (textures/texel_slope_steps.hpp):
// every code covers the step it was made from, within an eighth of an octave, and every texel's
// bound covers the true step to each of its four neighbours, across the map's edges too.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "textures/generators.hpp"
#include "textures/texel_slope_steps.hpp"

namespace test_texel_slope_steps {

using namespace thx::tex;

TEST(TexelSlopeSteps, ACodeCoversItsStepWithinAnEighthOfAnOctave) {
  EXPECT_EQ(TexelSlopeSteps::encode(0.0), 0);
  EXPECT_EQ(TexelSlopeSteps::decode(0), 0.0);
  for (double step = 1e-7; step < 100.0; step *= 1.0137) {
    const double bound = TexelSlopeSteps::decode(TexelSlopeSteps::encode(step));
    EXPECT_GE(bound, step) << step;
    EXPECT_LE(bound, step * std::exp2(1.0 / 8.0) * (1 + 1e-12)) << step;
  }
  // Too small for a code of its own: the smallest code, still above it.
  EXPECT_EQ(TexelSlopeSteps::encode(1e-12), 1);
  EXPECT_GE(TexelSlopeSteps::decode(1), 1e-12);
  // Too large, infinite or not a number: a bound no angle passes.
  for (double bad : {1e3, HUGE_VAL, std::nan("")}) {
    EXPECT_EQ(TexelSlopeSteps::encode(bad), 255) << bad;
  }
  EXPECT_TRUE(std::isinf(TexelSlopeSteps::decode(255)));
}

TEST(TexelSlopeSteps, AFlatMapHasNoStep) {
  const TexelSlopeSteps steps(TextureMap(6, 4, Representation::Normal));
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 6; ++i) EXPECT_EQ(steps.bound(i, j), 0.0);
  EXPECT_EQ(steps.bytes(), 2u);  // two tiles of 4 x 4 texels, the second only half used
}

// The step between two texels' slopes as TextureMap::normal decodes them.
double stepBetween(const TextureMap& map, int i, int j, int k, int l) {
  const Eigen::Vector3d a = map.normal(i, j).cast<double>(), b = map.normal(k, l).cast<double>();
  return std::hypot(a.x() / a.z() - b.x() / b.z(), a.y() / a.z() - b.y() / b.z());
}

TEST(TexelSlopeSteps, EveryTexelsBoundCoversItsNeighboursAcrossTheEdges) {
  for (const char* kind : {"vvalley", "pebbles", "sine"}) {
    GenerateRequest r;
    r.kind = kind;
    r.size = 50;  // tiles of 4 do not divide it: the last row and column of tiles are partly used
    r.params["extent"] = 0.05;
    const TextureMap map = generate(r);
    const TexelSlopeSteps steps(map);
    const int w = map.width(), h = map.height(), t = TexelSlopeSteps::kTile;
    std::vector<double> tile_step(std::size_t(((w + t - 1) / t) * ((h + t - 1) / t)), 0.0);
    for (int j = 0; j < h; ++j) {
      for (int i = 0; i < w; ++i) {
        double step = 0.0;
        step = std::max(step, stepBetween(map, i, j, (i + 1) % w, j));
        step = std::max(step, stepBetween(map, i, j, (i + w - 1) % w, j));
        step = std::max(step, stepBetween(map, i, j, i, (j + 1) % h));
        step = std::max(step, stepBetween(map, i, j, i, (j + h - 1) % h));
        // (The steps are taken as the square root of squared differences: within an ulp of hypot.)
        ASSERT_GE(steps.bound(i, j) * (1 + 1e-12), step) << kind << " texel " << i << ", " << j;
        double& tile = tile_step[std::size_t((j / t) * ((w + t - 1) / t) + i / t)];
        tile = std::max(tile, step);
      }
    }
    // Each tile's bound is its largest step, rounded up by at most an eighth of an octave.
    double largest = 0.0;
    for (int j = 0; j < h; ++j) {
      for (int i = 0; i < w; ++i) {
        const double tile = tile_step[std::size_t((j / t) * ((w + t - 1) / t) + i / t)];
        ASSERT_LE(steps.bound(i, j), tile * 1.1) << kind << " texel " << i << ", " << j;
        largest = std::max(largest, tile);
      }
    }
    EXPECT_GT(largest, 0.01) << kind;  // the map does turn
  }
}

}  // namespace test_texel_slope_steps
