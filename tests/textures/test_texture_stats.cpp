// Texture statistics for `texturetool info` (textures/texture_stats.hpp).
#include <gtest/gtest.h>

#include <cmath>

#include "textures/generators.hpp"
#include "textures/texture_stats.hpp"

namespace test_texture_stats {

using namespace thx::tex;

// 90° V-valleys: every wall is 45° steep, the depth ramps uniformly between ridge and floor.
TEST(TextureStats, VValleyHasUniform45DegreeWalls) {
  const TextureMap m = generate({"vvalley", 100, {{"angle_deg", 90}, {"period", 0.004}, {"extent", 0.04}}, 1});
  const TextureStats s = computeStats(m);
  EXPECT_EQ(s.width, 100);
  EXPECT_EQ(s.representation, Representation::Relief);
  EXPECT_NEAR(s.steepest_deg, 45.0, 0.01);
  EXPECT_NEAR(s.mean_tilt_deg, 45.0, 0.01);
  EXPECT_NEAR(s.mean_nz, std::sqrt(0.5), 1e-4);
  EXPECT_EQ(s.steep_texels, 0u);
  EXPECT_EQ(s.depth_min_m, 0.0);
  EXPECT_NEAR(s.depth_max_m, m.maxDepth(), 1e-9);  // float depth decoding
  EXPECT_NEAR(s.depth_mean_m, m.maxDepth() / 2, m.maxDepth() * 0.01);
}

TEST(TextureStats, CountsTexelsSteeperThanTheThreshold) {
  TextureMap m(10, 10, Representation::Normal);
  const double tilt = 70.0 * 3.14159265358979323846 / 180;
  for (int i = 0; i < 10; ++i) m.setNormal(i, 3, Eigen::Vector3f(float(std::sin(tilt)), 0.0f, float(std::cos(tilt))));
  const TextureStats s = computeStats(m, 60.0);
  EXPECT_EQ(s.steep_texels, 10u);
  EXPECT_NEAR(s.steepest_deg, 70.0, 0.01);
  EXPECT_EQ(s.steepest_texel.j, 3);
  EXPECT_NEAR(s.mean_tilt_deg, 7.0, 0.01);
  EXPECT_EQ(computeStats(m, 75.0).steep_texels, 0u);
  const std::string text = formatStats(s);
  EXPECT_NE(text.find("10 x 10"), std::string::npos) << text;
  EXPECT_NE(text.find("normal"), std::string::npos) << text;
  EXPECT_EQ(text.find("max depth"), std::string::npos) << text;  // normal maps have no depth
}

}  // namespace test_texture_stats
