// A ball with a bump map's basins are found reading its texture only as far out from its lowest
// point as they can lie (clients/physics/textured_ball_basins.hpp): the basins chosen are those the
// whole touching disc gives, to the bit, on flat and bent ground, within a chart's edges or not,
// for bumps, dimples and a uniform recess, the ball touching, sunk or hovering within reach.
#include <gtest/gtest.h>

#include <array>
#include <random>
#include <string>

#include "clients/physics/chart_boundary.hpp"
#include "clients/physics/speculative_contacts.hpp"
#include "clients/physics/textured_ball_basins.hpp"
#include "tests/physics/random_chart_boundary.hpp"
#include "tests/physics/textured_ball_scene.hpp"

namespace thx::phys::test::test_textured_ball_basins {
namespace {

using namespace textured_ball;

// Bullet's breaking threshold for the 1 cm ball against a plane (relief_collision.cpp reads it).
constexpr double kExtent = 0.04, kThreshold = 3.46e-4;

// The basins as the whole disc gives them: every texel within the threshold read; the four
// closest to closing, then those open by less than `closing`, up to kMaxBallBasins.
BallBasins wholeDisc(const tex::TexturedSurface& surface, const Underside& ball, const FaceTexture& texture,
                     double closing, const GroundBend* bend, const ChartBoundary* boundary,
                     std::vector<ReliefCandidate>& candidates) {
  BallBasins b;
  candidates.clear();
  b.raster = rasterizeRelief(surface, ball, kThreshold, candidates, &texture, bend, false, boundary);
  dropPastBoundary(boundary, candidates);
  const std::size_t all = selectShallowestBasins(candidates, b.raster.stride_i, b.raster.stride_j, b.picked);
  for (std::size_t k = 0; k < all; ++k)
    if (k < 4 || candidates[b.picked[k]].depth < closing) b.count = k + 1;
  b.passes = 1;
  return b;
}

// Each configuration a short run of poses (the ball rolling and sinking a little each step) with
// the hint carried along, as the collision algorithm carries it, and once more with a hint that
// says nothing true (none, zero, negative, far too small, beyond the threshold); the further
// basins kept below no gap, the 20 µm of a 1 ms step, or one beyond the threshold.
TEST(TexturedBallBasins, ReadOnlyAsFarOutAsTheyCanLieTheyAreTheWholeDiscsToTheBit) {
  const tex::TextureMap bumpy = bumpMap(3e-4), dimpled = dimpleMap(), recessed = uniformRecess(5e-4);
  const std::array<FaceTexture, 3> textures = {ballTexture(bumpy), ballTexture(dimpled), ballTexture(recessed)};
  const SurfaceHolder flat = holdSurface(flatRelief(128), kExtent, true);
  const SurfaceHolder bumpy_plane =
      holdSurface(heightMap(256, kExtent, [](double x, double y) { return bumps(x, y, 4e-4, 0.002); }), kExtent, true);
  GroundBend bowl, dome;
  bowl.xx = 14.0, bowl.yy = 15.0, bowl.xy = 0.3;
  dome.xx = -96.0, dome.yy = -95.0, dome.xy = 1.4;
  const std::array<double, 6> untrue_hints = {std::nan(""), 0.0, -1e-3, 1e-7, 2e-4, 1.0};
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const std::array<double, 3> closings = {0.0, closableGap(1e-3), 2.0 * kThreshold};
  std::size_t compared = 0, on_the_bound = 0, fell_back = 0, whole_at_once = 0, past_the_fourth = 0;
  for (int round = 0; round < 24; ++round) {
    Eigen::Isometry3d start = Eigen::Isometry3d::Identity();
    start.linear() = Eigen::Quaterniond(Eigen::Vector4d(unit(rng), unit(rng), unit(rng), unit(rng)).normalized()).toRotationMatrix();
    // Mostly touching (within 50 µm either way), some sunk 0.3 mm or hovering beyond the threshold.
    const double offset = round % 4 == 0 ? 4e-4 * unit(rng) : 5e-5 * unit(rng);
    start.translation() = Eigen::Vector3d(0.004 * unit(rng), 0.004 * unit(rng), kRadius + offset);
    const Eigen::Vector3d roll(unit(rng), unit(rng), 0.0);
    const ChartBoundary edges = randomBoundary(rng, start.translation().head<2>());
    const double closing = closings[std::size_t(round) % closings.size()];
    for (const FaceTexture& texture : textures)
      for (const SurfaceHolder* ground : {&flat, &bumpy_plane})
        for (const GroundBend* bend : std::array<const GroundBend*, 3>{nullptr, &bowl, &dome})
          for (const ChartBoundary* boundary : std::array<const ChartBoundary*, 2>{nullptr, &edges}) {
            BallBasinHint carried;
            for (int step = 0; step < 8; ++step) {
              // Rolled 0.1 mm a step (turned by 0.1 mm / r), sinking 2 µm a step.
              Eigen::Isometry3d pose = start;
              const double s = 1e-4 * step;
              pose.translation() += s * roll.normalized() - Eigen::Vector3d(0.0, 0.0, 2e-6 * step);
              pose.linear() = Eigen::AngleAxisd(s / kRadius, Eigen::Vector3d::UnitZ().cross(roll).normalized()).toRotationMatrix() *
                              start.linear();
              const Underside ball = Underside::sphere(pose, kRadius);
              std::vector<ReliefCandidate> all;
              const BallBasins expected = wholeDisc(ground->surface, ball, texture, closing, bend, boundary, all);
              BallBasinHint untrue;
              untrue.reach_m = untrue_hints[std::size_t(step) % untrue_hints.size()];
              for (BallBasinHint* hint : {&carried, &untrue}) {
                std::vector<ReliefCandidate> found;
                const BallBasins got =
                    findBallBasins(ground->surface, ball, texture, kThreshold, closing, bend, boundary, *hint, found);
                const std::string what = "round " + std::to_string(round) + " step " + std::to_string(step) +
                                         (hint == &carried ? " carried" : " untrue");
                ASSERT_EQ(expected.count, got.count) << what;
                for (std::size_t k = 0; k < got.count; ++k) {
                  const ReliefCandidate &e = all[expected.picked[k]], &g = found[got.picked[k]];
                  EXPECT_EQ(e.i, g.i) << what << " basin " << k;
                  EXPECT_EQ(e.j, g.j) << what << " basin " << k;
                  EXPECT_EQ(e.depth, g.depth) << what << " basin " << k;
                  EXPECT_EQ(e.p_surface, g.p_surface) << what << " basin " << k;
                  // Read for the basins kept (withNormals) from the texel and point compared here.
                  EXPECT_FALSE(hasNormal(e) || hasNormal(g)) << what << " basin " << k;
                }
                compared += got.count;
                if (got.count > 4) ++past_the_fourth;
                if (!got.whole_disc) ++on_the_bound;
                else if (got.passes == 2) ++fell_back;
                else ++whole_at_once;
              }
            }
          }
  }
  std::printf("[measured] ball basins: %zu compared; found within the bound %zu times, read the whole disc after "
              "the bound %zu, at once %zu; more than four kept %zu times\n",
              compared, on_the_bound, fell_back, whole_at_once, past_the_fourth);
  // Every way through the search was taken, and enough of each to mean something.
  EXPECT_GT(compared, 10000u);
  EXPECT_GT(on_the_bound, 100u);
  EXPECT_GT(fell_back, 100u);
  EXPECT_GT(whole_at_once, 100u);
  EXPECT_GT(past_the_fourth, 100u);
}

}  // namespace
}  // namespace thx::phys::test::test_textured_ball_basins
