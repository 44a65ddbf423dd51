// The relief raster visits a row only where its candidates can lie (clients/physics/relief_raster.hpp):
// within a ball's touching disc, and not past a mesh chart's edges (chart_boundary.hpp). Neither
// may change what it finds: the candidates are those every texel of the footprint would give, less
// those past the chart's edges, to the bit; and their normals, read in the raster or afterwards
// (withNormals), are the same to the bit.
#include <gtest/gtest.h>

#include <array>
#include <optional>
#include <random>
#include <string>

#include "clients/physics/chart_boundary.hpp"
#include "clients/physics/relief_raster.hpp"
#include "tests/physics/random_chart_boundary.hpp"
#include "tests/physics/textured_ball_scene.hpp"

namespace thx::phys::test::test_relief_raster_rows {
namespace {

using textured_ball::ballTexture;
using textured_ball::bumpMap;
using textured_ball::bumps;

constexpr double kExtent = 0.04, kThreshold = 3e-4;

Eigen::Isometry3d randomPose(std::mt19937& rng, double height) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  Eigen::Isometry3d at = Eigen::Isometry3d::Identity();
  at.linear() = Eigen::Quaterniond(Eigen::Vector4d(unit(rng), unit(rng), unit(rng), unit(rng)).normalized()).toRotationMatrix();
  at.translation() = Eigen::Vector3d(0.004 * unit(rng), 0.004 * unit(rng), height + 3e-4 * unit(rng));
  return at;
}

void expectSameCandidates(const std::vector<ReliefCandidate>& expected, const std::vector<ReliefCandidate>& got,
                          const std::string& what) {
  ASSERT_EQ(expected.size(), got.size()) << what;
  for (std::size_t k = 0; k < got.size(); ++k) {
    EXPECT_EQ(expected[k].i, got[k].i) << what << " " << k;
    EXPECT_EQ(expected[k].j, got[k].j) << what << " " << k;
    EXPECT_EQ(expected[k].depth, got[k].depth) << what << " " << k;
    EXPECT_EQ(expected[k].p_surface, got[k].p_surface) << what << " " << k;
    EXPECT_EQ(expected[k].n_local, got[k].n_local) << what << " " << k;
  }
}

TEST(ReliefRasterRows, WithinAChartsEdgesItFindsTheCandidatesPastThemDroppedToTheBit) {
  const SurfaceHolder plane =
      holdSurface(heightMap(256, kExtent, [](double x, double y) { return bumps(x, y, 4e-4, 0.002); }), kExtent, true);
  const tex::TextureMap ball_map = bumpMap(3e-4);
  const FaceTexture texture = ballTexture(ball_map);
  GroundBend bowl, dome;
  bowl.xx = 14.0, bowl.yy = 15.0, bowl.xy = 0.3;
  dome.xx = -196.0, dome.yy = -195.0, dome.xy = 1.4;
  std::mt19937 rng(5);
  std::size_t compared = 0, dropped = 0;
  long long visited_all = 0, visited_within = 0;
  for (int round = 0; round < 60; ++round) {
    const double r = 0.006;
    std::vector<Underside> shapes = {
        Underside::sphere(randomPose(rng, r - 2e-4), r),
        Underside::box(randomPose(rng, 0.004), Eigen::Vector3d(0.006, 0.005, 0.004)),
        Underside::capsule(randomPose(rng, 0.003), 0.003, 0.005, int(rng() % 3)),
        Underside::cylinder(randomPose(rng, 0.004), 0.003, 0.004, int(rng() % 3)),
    };
    for (const Underside& shape : shapes) {
      const ChartBoundary boundary = randomBoundary(rng, shape.plane_from_object.translation().head<2>());
      const bool can_texture = shape.kind == Underside::Kind::Sphere || shape.kind == Underside::Kind::Box;
      for (const GroundBend* bend : std::array<const GroundBend*, 3>{nullptr, &bowl, &dome}) {
        for (const FaceTexture* object : std::array<const FaceTexture*, 2>{nullptr, &texture}) {
          if (object && !can_texture) continue;
          std::vector<ReliefCandidate> with_normals;
          for (const bool normals : {true, false}) {
            std::vector<ReliefCandidate> all, within;
            const RasterStats everywhere = rasterizeRelief(plane.surface, shape, kThreshold, all, object, bend, normals);
            const RasterStats clipped =
                rasterizeRelief(plane.surface, shape, kThreshold, within, object, bend, normals, &boundary);
            const std::string what = "round " + std::to_string(round) + " shape " + std::to_string(int(shape.kind)) +
                                     (normals ? "" : ", normals read after");
            if (normals) {
              with_normals = all;
            } else {
              // Read afterwards, the normals are those read in the raster, to the bit.
              const std::optional<TexturedObjectSurface> on_object =
                  object ? std::optional<TexturedObjectSurface>(std::in_place, shape, *object) : std::nullopt;
              for (std::vector<ReliefCandidate>* found : {&all, &within})
                for (ReliefCandidate& c : *found) {
                  EXPECT_FALSE(hasNormal(c)) << what;
                  withNormals(plane.surface, bend, on_object ? &*on_object : nullptr, c);
                }
              expectSameCandidates(with_normals, all, what);
            }
            const std::size_t before = all.size();
            std::erase_if(all, [&](const ReliefCandidate& c) { return boundary.past(c.p_surface); });
            dropped += before - all.size();
            expectSameCandidates(all, within, what);
            compared += within.size();
            visited_all += everywhere.texels_visited, visited_within += clipped.texels_visited;
          }
        }
      }
    }
  }
  // Enough of each kind to mean something, and the edges cut real candidates away.
  EXPECT_GT(compared, 20000u);
  EXPECT_GT(dropped, 20000u);
  EXPECT_LT(visited_within, visited_all);
}

// The ball's rows are visited only within its touching disc: every texel of its footprint whose
// depth (the ball's lowest point over the texel's centre less the relief's height there) is below
// the threshold is a candidate, and no other, found here texel by texel.
TEST(ReliefRasterRows, ABallsCandidatesAreEveryTexelOfItsFootprintWithinTheThreshold) {
  const SurfaceHolder plane =
      holdSurface(heightMap(256, kExtent, [](double x, double y) { return bumps(x, y, 4e-4, 0.002); }), kExtent, true);
  std::mt19937 rng(9);
  std::size_t compared = 0;
  for (int round = 0; round < 40; ++round) {
    const double r = 0.002 + 0.001 * double(round % 5);
    const Underside ball = Underside::sphere(randomPose(rng, r - 2e-4), r);
    std::vector<ReliefCandidate> found;
    rasterizeRelief(plane.surface, ball, kThreshold, found);
    std::vector<std::pair<long long, long long>> expected;
    const long long n = 256;
    for (long long j = 0; j < n; ++j)
      for (long long i = 0; i < n; ++i) {
        const tex::TexelPoint t = plane.surface.texelPoint(i, j);
        const std::optional<double> z = lowestZ(ball, t.q_local.x(), t.q_local.y());
        if (z && *z - t.q_local.z() < kThreshold) expected.emplace_back(i, j);
      }
    ASSERT_EQ(found.size(), expected.size()) << round;
    for (std::size_t k = 0; k < found.size(); ++k) {
      // The plane wraps: the raster's indices are unwrapped.
      EXPECT_EQ(((found[k].i % n) + n) % n, expected[k].first) << round << " " << k;
      EXPECT_EQ(((found[k].j % n) + n) % n, expected[k].second) << round << " " << k;
      EXPECT_NEAR(found[k].depth, lowestZ(ball, found[k].p_surface.x(), found[k].p_surface.y()).value() - found[k].p_surface.z(),
                  1e-12);
    }
    compared += found.size();
  }
  EXPECT_GT(compared, 1000u);
}

}  // namespace
}  // namespace thx::phys::test::test_relief_raster_rows
