// Eq. 5 meso impulses over a texel path (clients/audio/synthesis/meso_impulses.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "clients/audio/synthesis/meso_impulses.hpp"

namespace thx::audio::test_meso_impulses {
namespace {

// A bumpy map: every texel's normal tilted by a deterministic pseudo-random amount.
tex::TextureMap bumpyMap(int w, int h) {
  tex::TextureMap map(w, h, tex::Representation::Normal);
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i)
      map.setNormal(i, j, Eigen::Vector3f(0.3f * std::sin(float(i * 7 + j * 3)), 0.3f * std::cos(float(i * 5 - j * 11)), 1.0f));
  return map;
}

// Texels entered along the path: changes of texel in the concatenated walks of its segments.
std::size_t texelsEntered(const tex::TextureMap& map, const std::vector<PathPoint>& path) {
  std::vector<tex::TexelIndex> cells;
  for (std::size_t k = 1; k < path.size(); ++k)
    for (tex::TexelIndex t : tex::texelsOnSegment(map, path[k - 1].uv, path[k].uv, tex::Address::Wrap))
      if (cells.empty() || !(cells.back() == t)) cells.push_back(t);
  return cells.empty() ? 0 : cells.size() - 1;
}

TEST(MesoImpulses, OneImpulsePerTexelEnteredEvenWhenFast) {
  const tex::TextureMap map = bumpyMap(32, 16);
  MesoSurface surface{&map, tex::Address::Wrap, {0, 0, 1}, 0.02, 0.05};
  // A wandering path with long (fast) steps, crossing the wrap seam.
  const std::vector<PathPoint> path{{{0.05, 0.10}, {0.3, 0.1, 0}},
                                    {{0.61, 0.37}, {0.9, 0.2, 0}},   // 18 columns and 4 rows in one step
                                    {{0.63, 0.38}, {0.1, 0.0, 0}},
                                    {{1.40, 0.02}, {1.5, -0.4, 0}},  // across the seam
                                    {{1.38, 0.90}, {-0.1, 0.8, 0}}};
  const std::vector<MesoImpulse> impulses = mesoImpulses(surface, path);
  EXPECT_EQ(impulses.size(), texelsEntered(map, path));
  EXPECT_GT(impulses.size(), 40u);
  // A straight run over 20 columns in one segment: 20 impulses, none skipped.
  const std::vector<PathPoint> run{{{0.5 / 32, 0.5}, {2, 0, 0}}, {{20.5 / 32, 0.5}, {2, 0, 0}}};
  EXPECT_EQ(mesoImpulses(surface, run).size(), 20u);
}

TEST(MesoImpulses, FlatMapGivesExactlyZero) {
  const tex::TextureMap map(16, 16, tex::Representation::Normal);
  MesoSurface surface{&map, tex::Address::Wrap, {0, 0, 1}, 0.05, 0.05};
  // Velocities with a normal component too: only the tangential part counts, and it is
  // perpendicular to every flat texel's normal.
  const std::vector<PathPoint> path{{{0.1, 0.1}, {0.3, 0.2, 0.1}}, {{0.9, 0.7}, {-0.7, 0.3, -0.2}}, {{0.2, 0.3}, {1.1, 2.0, 0.5}}};
  const std::vector<MesoImpulse> impulses = mesoImpulses(surface, path);
  EXPECT_EQ(impulses.size(), texelsEntered(map, path));
  for (const MesoImpulse& m : impulses) EXPECT_EQ(m.impulse, Eigen::Vector3d::Zero());
}

// Column 3 tilted by 20 degrees about y; the contact slides along +x at 0.4 m/s (and 0.1 m/s
// along y, which the tilt does not see), m = 0.05 kg, n_g = z.
// Entering the tilted column: p_n = m (-(v . n_s) / (n_g . n_s)) n_g = -m v_x tan(20 deg) z
//   = -0.05 * 0.4 * 0.3639702 = -7.279405e-3 N s along z; leaving it gives the opposite.
TEST(MesoImpulses, TiltedColumnMagnitudeByHand) {
  tex::TextureMap map(8, 8, tex::Representation::Normal);
  const float theta = 20.0f * std::numbers::pi_v<float> / 180.0f;
  for (int j = 0; j < 8; ++j) map.setNormal(3, j, Eigen::Vector3f(std::sin(theta), 0.0f, std::cos(theta)));
  MesoSurface surface{&map, tex::Address::Wrap, {0, 0, 1}, 0.05, 0.05};
  const Eigen::Vector3d v(0.4, 0.1, 0.0);
  const std::vector<PathPoint> path{{{1.5 / 8, 0.44}, v}, {{5.5 / 8, 0.48}, v}};  // all in row 4
  const std::vector<MesoImpulse> impulses = mesoImpulses(surface, path);
  ASSERT_EQ(impulses.size(), 4u);  // columns 2, 3, 4, 5 entered
  const double expected = -7.279405e-3;
  // The stored normal is 16-bit fixed point: 1e-4 relative.
  EXPECT_EQ(impulses[0].impulse, Eigen::Vector3d::Zero());
  EXPECT_EQ(impulses[1].texel.i, 3);
  EXPECT_NEAR(impulses[1].impulse.z(), expected, 1e-4 * std::fabs(expected));
  EXPECT_EQ(impulses[1].impulse.x(), 0.0);
  EXPECT_EQ(impulses[1].impulse.y(), 0.0);
  EXPECT_NEAR(impulses[2].impulse.z(), -expected, 1e-4 * std::fabs(expected));
  EXPECT_EQ(impulses[3].impulse, Eigen::Vector3d::Zero());
  // Moving the other way reverses the sign.
  const std::vector<PathPoint> back{{{5.5 / 8, 0.46}, -v}, {{1.5 / 8, 0.46}, -v}};
  EXPECT_NEAR(mesoImpulses(surface, back)[1].impulse.z(), -expected, 1e-4 * std::fabs(expected));
}

// As the sampled normal approaches the tangent plane, n_g . n_s -> 0: the floor keeps p_n below
// m |v_t| / min_normal_dot.
TEST(MesoImpulses, BoundedAsTheNormalsBecomePerpendicular) {
  tex::TextureMap map(4, 4, tex::Representation::Normal);
  for (int j = 0; j < 4; ++j) map.setNormal(1, j, Eigen::Vector3f(1.0f, 0.0f, 1e-6f));  // stored z = 1e-3
  const double mass = 0.05, speed = 2.0, floor = 0.05;
  MesoSurface surface{&map, tex::Address::Wrap, {0, 0, 1}, mass, floor};
  const std::vector<PathPoint> path{{{0.5 / 4, 0.5}, {speed, 0, 0}}, {{2.5 / 4, 0.5}, {speed, 0, 0}}};
  const std::vector<MesoImpulse> impulses = mesoImpulses(surface, path);
  ASSERT_EQ(impulses.size(), 2u);
  for (const MesoImpulse& m : impulses) {
    EXPECT_TRUE(m.impulse.allFinite());
    EXPECT_LE(m.impulse.norm(), mass * speed / floor * (1 + 1e-12));
    EXPECT_GT(m.impulse.norm(), 0.9 * mass * speed / floor);  // it is the floor that limits it
  }
}

}  // namespace
}  // namespace thx::audio::test_meso_impulses
