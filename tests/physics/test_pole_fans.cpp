// The fans of triangles round a pole of the uv (clients/physics/mesh_relief_chart.hpp, poleFans):
// where a relief's chart is smooth, the texture having no one layout there.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "clients/physics/mesh_relief_chart.hpp"
#include "meshes/mesh_generators.hpp"
#include "meshes/textured_ball_mesh.hpp"
#include "meshes/textured_box_mesh.hpp"

namespace {

using thx::mesh::TexturedMesh;
using thx::phys::kPoleFan;
using thx::phys::kPoleRing;

struct Counts {
  int fan = 0, ring = 0;
  double farthest_fan_m = 0.0;  // the fan's corners' largest distance from the z axis
};

Counts count(const TexturedMesh& m) {
  const thx::phys::MeshRelief relief(m);
  Counts c;
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    if (relief.pole[t] == kPoleFan) {
      ++c.fan;
      for (std::uint32_t v : m.triangles[t]) c.farthest_fan_m = std::max(c.farthest_fan_m, m.positions[v].head<2>().norm());
    }
    if (relief.pole[t] == kPoleRing) ++c.ring;
  }
  return c;
}

TEST(PoleFans, AUvSpheresTwoPolesAreFansOfTheirSegmentsEach) {
  const Counts c = count(thx::mesh::sphere(0.05, 32, 16, 0.01).mesh);
  EXPECT_EQ(c.fan, 2 * 32);
  // The first ring of latitude, 1/16 of the way round from each pole.
  EXPECT_NEAR(c.farthest_fan_m, 0.05 * std::sin(M_PI / 16), 1e-9);
  // The fan's ring: the next band of quads (two triangles each) round each pole.
  EXPECT_EQ(c.ring, 2 * 2 * 32);
}

TEST(PoleFans, ABowlsTwoCentresAreFans) {
  const TexturedMesh bowl = thx::mesh::lathe(thx::mesh::bowlProfile(0.06, 0.048, 0.0048, 32), 64, 0.04).mesh;
  const Counts c = count(bowl);
  EXPECT_EQ(c.fan, 2 * 64);  // the floor's centre inside and the foot's outside
  EXPECT_LT(c.farthest_fan_m, 0.01);
}

TEST(PoleFans, AtlasSeamsWrappedSeamsAndHardEdgesAreNoPoles) {
  // A cube-sphere's corners hold three faces' uv, and a box's corners three faces' with their
  // normals apart; a torus and a tube wrap their uv round whole tiles.
  EXPECT_EQ(count(thx::mesh::texturedBallMesh(0.01, 0.02, 12)).fan, 0);
  EXPECT_EQ(count(thx::mesh::texturedBoxMesh(Eigen::Vector3d(0.02, 0.03, 0.01), 0.02)).fan, 0);
  EXPECT_EQ(count(thx::mesh::box(Eigen::Vector3d(0.02, 0.03, 0.01), 0.005, 0.02).mesh).fan, 0);
  EXPECT_EQ(count(thx::mesh::torus(0.05, 0.02, 32, 16, 0.01).mesh).fan, 0);
  EXPECT_EQ(count(thx::mesh::cylinder(0.02, 0.05, 32, 8, 0.01).mesh).fan, 0);
}

// By the pole a relief's chart is smooth: on the fan, and on its ring while the object came from
// the fan; beyond the ring, and on it when the object came from beyond, the texture is laid.
TEST(PoleFans, AReliefsChartIsSmoothOnThePolesFanAndStaysSoOnItsRing) {
  const TexturedMesh bowl = thx::mesh::lathe(thx::mesh::bowlProfile(0.06, 0.048, 0.0048, 32), 64, 0.04).mesh;
  const thx::tex::TextureMap relief_map(64, 64, thx::tex::Representation::Relief, 1e-3);
  thx::phys::MeshRelief relief(bowl);
  relief.map = &relief_map;
  // Over the inside floor (4.8 mm up, its first ring 2.7 mm from the axis, the next 5.4 mm).
  auto chartAt = [&](double rho_m, bool& by_pole) {
    std::uint32_t triangle = thx::mesh::kNoNeighbour;
    thx::phys::MeshChart chart;
    EXPECT_TRUE(thx::phys::chartUnder(relief, Eigen::Vector3d(rho_m, 0.0, 0.0098), 0.005, triangle, by_pole, chart));
    EXPECT_EQ(chart.smooth, by_pole);
    return relief.pole[triangle];
  };
  bool by_pole = false;
  EXPECT_EQ(chartAt(0.004, by_pole), kPoleRing);
  EXPECT_FALSE(by_pole);  // came from beyond
  EXPECT_EQ(chartAt(0.001, by_pole), kPoleFan);
  EXPECT_TRUE(by_pole);
  EXPECT_EQ(chartAt(0.004, by_pole), kPoleRing);
  EXPECT_TRUE(by_pole);  // came from the fan
  EXPECT_EQ(chartAt(0.008, by_pole), 0);
  EXPECT_FALSE(by_pole);
  // The smooth chart's samples no finer than the relief's coarser texel there (v's: 4 cm / 64).
  std::uint32_t triangle = thx::mesh::kNoNeighbour;
  thx::phys::MeshChart chart;
  by_pole = true;
  ASSERT_TRUE(thx::phys::chartUnder(relief, Eigen::Vector3d(0.001, 0.0, 0.0098), 0.005, triangle, by_pole, chart));
  EXPECT_NEAR(chart.least_cell_m, 0.04 / 64, 0.04 / 64 * 0.05);
}

}  // namespace
