// A relief as a ball meets it (textures/ball_on_relief.hpp): the centre of a ball of radius r at
// max over t of [h(t) + sqrt(r^2 - |x - t|^2)], the normal from the point it touches.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <random>
#include <vector>

#include "textures/ball_on_relief.hpp"
#include "textures/height_normals.hpp"

namespace thx::tex::test_ball_on_relief {
namespace {

constexpr double kTexel = 1e-4;  // 0.1 mm texels: a 128-texel tile is 12.8 mm

// A relief of heights h(i, j) in metres, kTexel texels.
template <class Height>
TextureMap reliefOf(int w, int h, Height height) {
  HeightField field;
  field.width = w;
  field.height = h;
  field.heights_m.resize(std::size_t(w) * std::size_t(h));
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) field.heights_m[std::size_t(j) * std::size_t(w) + std::size_t(i)] = height(i, j);
  ReliefFromHeightOptions o;
  o.texel_m = {kTexel, kTexel};
  o.address = Address::Wrap;
  return reliefFromHeight(field, o);
}

// Brute force: the highest the ball's centre is lifted over any texel centre (no refinement),
// over every wrapped image within r; with a half (BallOnRelief::Half), over its texels alone:
// along u, (i - s) * sign >= 0; along v, whose rows run against it, (t - j) * sign >= 0.
// `widen`: texels that far beyond the line count too.
double bruteForceLiftOnHalf(const TextureMap& map, TexCoord uv, const Eigen::Vector2d& metres_per_uv, double r,
                            BallOnRelief::Half half, double widen = 0.0) {
  const double s = uv.u * map.width() - 0.5, t = (1.0 - uv.v) * map.height() - 0.5;
  const double du = metres_per_uv.x() / map.width(), dv = metres_per_uv.y() / map.height();
  const int ru = int(std::ceil(r / du)) + 1, rv = int(std::ceil(r / dv)) + 1;
  double best = -1e300;
  for (long long j = (long long)std::floor(t) - rv; j <= (long long)std::floor(t) + rv; ++j)
    for (long long i = (long long)std::floor(s) - ru; i <= (long long)std::floor(s) + ru; ++i) {
      if (half.axis == 0 && (double(i) - s) * half.sign < -widen) continue;
      if (half.axis == 1 && (t - double(j)) * half.sign < -widen) continue;
      const double d2 = std::pow((double(i) - s) * du, 2) + std::pow((double(j) - t) * dv, 2);
      if (d2 >= r * r) continue;
      const double h = -double(map.depth(resolveIndex(i, map.width(), Address::Wrap), resolveIndex(j, map.height(), Address::Wrap)));
      best = std::max(best, h + std::sqrt(r * r - d2));
    }
  return best - r;
}

double bruteForceLift(const TextureMap& map, TexCoord uv, const Eigen::Vector2d& metres_per_uv, double r) {
  return bruteForceLiftOnHalf(map, uv, metres_per_uv, r, BallOnRelief::Half{});
}

TEST(BallOnRelief, TheSearchFindsTheHighestTouchOfABruteForceScanAndTheRefinementOnlyLiftsIt) {
  // Random bumps, 64 x 32 texels; metrics from as laid to a pole's squeeze of u by 50.
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const TextureMap map = reliefOf(64, 32, [&](int i, int j) {
    return 2e-4 * std::sin(0.7 * i + 0.3 * j) * std::cos(0.45 * j) + 5e-5 * std::sin(2.1 * i * j);
  });
  const BallOnRelief reader(map, Address::Wrap);
  for (int k = 0; k < 300; ++k) {
    const TexCoord uv{unit(rng) * 3.0 - 1.0, unit(rng) * 3.0 - 1.0};
    const double squeeze = k % 3 == 0 ? 1.0 : (k % 3 == 1 ? 0.1 : 0.02);
    const Eigen::Vector2d mpu(64 * kTexel * squeeze, 32 * kTexel);
    const double r = k % 2 ? 1e-3 : 4e-3;
    const BallOnRelief::Touch touch = reader.touch(uv, mpu, r);
    const double brute = bruteForceLift(map, uv, mpu, r);
    ASSERT_GE(touch.lift_m, brute - 1e-12) << k;
    // The refinement moves the touch within a texel of the best texel centre: it lifts the ball
    // by no more than a texel's worth of the relief's slope.
    ASSERT_LE(touch.lift_m, brute + 2e-5) << k;
    ASSERT_NEAR(touch.normal.norm(), 1.0, 1e-12) << k;
  }
}

// A search started from a texel touched nearby (`near`) finds the same touch to the bit: on
// random bumps, on terraces whose flat tops tie many texels, and on centres exactly between two
// texel centres (where two texels tie); wrapped and clamped, on halves, from behind; started from
// the texel a search a quarter texel away touched, from the true one, and from texels anywhere.
TEST(BallOnRelief, StartingFromATexelTouchedNearbyFindsTheSameTouchToTheBit) {
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const TextureMap bumps = reliefOf(64, 32, [&](int i, int j) {
    return 2e-4 * std::sin(0.7 * i + 0.3 * j) * std::cos(0.45 * j) + 5e-5 * std::sin(2.1 * i * j);
  });
  const TextureMap terraces = reliefOf(64, 32, [&](int i, int j) { return 1e-4 * double(((i / 8) + (j / 4)) % 3); });
  auto same = [](const std::optional<BallOnRelief::Touch>& a, const std::optional<BallOnRelief::Touch>& b) {
    if (a.has_value() != b.has_value()) return false;
    if (!a) return true;
    return a->lift_m == b->lift_m && a->normal == b->normal && a->texel.has_value() == b->texel.has_value() &&
           (!a->texel || (a->texel->i == b->texel->i && a->texel->j == b->texel->j));
  };
  int compared = 0, started_inside = 0;
  for (const TextureMap* map : {&bumps, &terraces})
    for (const Address address : {Address::Wrap, Address::Clamp}) {
      const BallOnRelief reader(*map, address);
      for (int k = 0; k < 400; ++k) {
        // Every fourth centre exactly between two texel centres along u.
        const double u = k % 4 == 0 ? (std::floor(unit(rng) * 64.0) + 1.0) / 64.0 : unit(rng) * 1.4 - 0.2;
        const TexCoord uv{u, unit(rng) * 1.4 - 0.2};
        const Eigen::Vector2d mpu(64 * kTexel * (k % 3 == 0 ? 1.0 : 0.1), 32 * kTexel);
        const double r = k % 2 ? 1e-3 : 4e-3;
        const bool behind = k % 5 == 0;
        const BallOnRelief::Half half =
            k % 7 == 0 ? BallOnRelief::Half{k % 2, k % 3 ? 1.0 : -1.0} : BallOnRelief::Half{};
        const std::optional<BallOnRelief::Touch> cold = reader.touchOnHalf(uv, mpu, r, behind, half);
        // The texel touched a quarter texel away along u and along v, the texel itself, and a
        // texel anywhere in or out of reach.
        std::vector<BallOnRelief::Texel> starts;
        for (const TexCoord& nearby : {TexCoord{uv.u + 0.25 / 64.0, uv.v}, TexCoord{uv.u, uv.v - 0.25 / 32.0}})
          if (const auto t = reader.touchOnHalf(nearby, mpu, r, behind, half); t && t->texel) starts.push_back(*t->texel);
        if (cold && cold->texel) starts.push_back(*cold->texel);
        starts.push_back({(long long)(unit(rng) * 200.0) - 70, (long long)(unit(rng) * 100.0) - 35});
        for (const BallOnRelief::Texel& start : starts) {
          const std::optional<BallOnRelief::Touch> warm = reader.touchOnHalf(uv, mpu, r, behind, half, start);
          ASSERT_TRUE(same(cold, warm)) << "centre " << k << " from texel " << start.i << ", " << start.j;
          ++compared;
        }
        if (cold && cold->texel) ++started_inside;
      }
    }
  EXPECT_GT(compared, 4000);
  EXPECT_GT(started_inside, 1000);
}

TEST(BallOnRelief, AFlatTopPushesStraightUpAndANarrowGrooveIsBridged) {
  // A groove 15 texels (1.5 mm) wide and 0.8 mm deep across u, every 64 texels.
  const TextureMap map = reliefOf(64, 64, [](int i, int) { return (i >= 40 && i < 55) ? -8e-4 : 0.0; });
  const BallOnRelief reader(map, Address::Wrap);
  const Eigen::Vector2d mpu(64 * kTexel, 64 * kTexel);
  const double r = 6e-3;
  // Over the top, between texel centres: straight up, the centre at r.
  for (double u : {0.1, 0.2037, 0.33}) {
    const BallOnRelief::Touch top = reader.touch({u, 0.4}, mpu, r);
    EXPECT_NEAR(top.normal.x(), 0.0, 1e-12) << u;
    EXPECT_NEAR(top.normal.y(), 0.0, 1e-12) << u;
    EXPECT_NEAR(top.lift_m, 0.0, 1e-12) << u;
  }
  // Over the groove the ball rests on its two edges (the last top texels' centres, 39 and 55):
  // it sinks by r - sqrt(r^2 - (w/2)^2) at the middle, far less than the groove's depth, and is
  // pushed away from the nearer edge. On a row's centre (v = 1 - 38.5 / 64) straight across it.
  const double middle = (47.0 + 0.5) / 64.0, half = 8.0 * kTexel;  // centres 39 and 55: 16 texels apart
  const double row = 1.0 - 38.5 / 64.0;
  const BallOnRelief::Touch at_middle = reader.touch({middle, row}, mpu, r);
  EXPECT_NEAR(at_middle.lift_m, -(r - std::sqrt(r * r - half * half)), 1e-9);
  EXPECT_GT(at_middle.lift_m, -1e-4);  // bridged: 0.8 mm deep, the ball sinks 5 µm
  const double x = 3.0 * kTexel;       // 3 texels right of the middle: nearer the right edge
  const BallOnRelief::Touch right = reader.touch({middle + 3.0 / 64.0, row}, mpu, r);
  EXPECT_NEAR(right.normal.x(), -(half - x) / r, 1e-9);
  EXPECT_NEAR(right.normal.y(), 0.0, 1e-12);
  // Between rows the touch slides along the edge to the centre's row: it does not lean along the
  // edge (before the step along one axis, it stayed on an edge texel's centre and leaned by up to
  // half a texel over r).
  const BallOnRelief::Touch between = reader.touch({middle + 3.0 / 64.0, row + 0.3 / 64.0}, mpu, r);
  EXPECT_NEAR(between.normal.x(), -(half - x) / r, 1e-6);
  EXPECT_NEAR(between.normal.y(), 0.0, 1e-9);
}

TEST(BallOnRelief, OnTwoCrestLinesTheLiftDoesNotRippleAlongThem) {
  // V-grooves along v, 40 texels (4 mm) apart and 1 mm deep, under a 5 mm ball over a groove's
  // floor: it rests on the two crests either side. Its touch slides along a crest to its centre's
  // row, so the lift is the same wherever the centre lies along the groove. (Before, the touch
  // stayed on a crest texel's centre, the refinement's step across the crest being refused, and
  // the lift rippled by 0.27 um a texel along the groove here, by 2.6 um under the same ball at
  // 0.31 mm texels: a ball rolled to and fro along such a groove at 4 mm/s.)
  const TextureMap map = reliefOf(80, 64, [](int i, int) { return -1e-3 * 2.0 * std::fabs(i / 40.0 - std::round(i / 40.0)); });
  const BallOnRelief reader(map, Address::Wrap);
  const Eigen::Vector2d mpu(80 * kTexel, 64 * kTexel);
  const double r = 5e-3;
  double lowest = 1.0, highest = -1.0;
  for (int k = 0; k <= 40; ++k) {
    const double v = 0.3 + k * (2.0 / 64.0) / 40.0;  // over two texels along the groove
    const BallOnRelief::Touch touch = reader.touch({20.5 / 80.0, v}, mpu, r);
    lowest = std::min(lowest, touch.lift_m);
    highest = std::max(highest, touch.lift_m);
    EXPECT_NEAR(touch.normal.y(), 0.0, 1e-9) << k;  // across the groove only
  }
  std::printf("[measured] along the groove: lift %.4f um, rippling by %.2e um\n", highest * 1e6, (highest - lowest) * 1e6);
  EXPECT_LT(highest - lowest, 1e-10);
  // On the crests 2 mm either side (the floor's texel centre 20, its neighbours' bilinear 20.5):
  // the centre sqrt(r^2 - (2 mm)^2) over their top.
  EXPECT_NEAR(highest, std::sqrt(r * r - 4e-6) - r, 1e-6);
}

TEST(BallOnRelief, TheNormalIsTheGradientOfTheLiftSoTheReadIsAPotential) {
  // Sine bumps 2.56 mm apart, amplitude 40 µm (slope 0.1), under a 1 cm ball; and the same
  // bumps squeezed 20 times along u, as at a mesh's pole.
  const double k = 2.0 * M_PI / 25.6;  // per texel
  const TextureMap map = reliefOf(128, 128, [&](int i, int j) { return 4e-5 * std::sin(k * i) * std::sin(k * j); });
  const BallOnRelief reader(map, Address::Wrap);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (double squeeze : {1.0, 0.05}) {
    const Eigen::Vector2d mpu(128 * kTexel * squeeze, 128 * kTexel);
    const double r = 0.01, h_u = 1e-3 / 128.0, h_v = 1e-3 / 128.0;  // steps of a thousandth of a texel
    double worst = 0.0, largest_slope_u = 0.0, largest_slope_v = 0.0;
    for (int n = 0; n < 200; ++n) {
      const TexCoord uv{unit(rng), unit(rng)};
      const BallOnRelief::Touch at = reader.touch(uv, mpu, r);
      const double du_m = h_u * mpu.x(), dv_m = h_v * mpu.y();
      const double gu = (reader.touch({uv.u + h_u, uv.v}, mpu, r).lift_m - reader.touch({uv.u - h_u, uv.v}, mpu, r).lift_m) / (2 * du_m);
      const double gv = (reader.touch({uv.u, uv.v + h_v}, mpu, r).lift_m - reader.touch({uv.u, uv.v - h_v}, mpu, r).lift_m) / (2 * dv_m);
      // A kink between two touches (the ball balanced between two crests) has no gradient.
      if (std::fabs(reader.touch({uv.u + h_u, uv.v}, mpu, r).normal.x() - reader.touch({uv.u - h_u, uv.v}, mpu, r).normal.x()) > 1e-3) continue;
      if (std::fabs(reader.touch({uv.u, uv.v + h_v}, mpu, r).normal.y() - reader.touch({uv.u, uv.v - h_v}, mpu, r).normal.y()) > 1e-3) continue;
      const double su = -at.normal.x() / at.normal.z(), sv = -at.normal.y() / at.normal.z();
      worst = std::max({worst, std::fabs(su - gu), std::fabs(sv - gv)});
      largest_slope_u = std::max(largest_slope_u, std::fabs(su));
      largest_slope_v = std::max(largest_slope_v, std::fabs(sv));
    }
    std::printf("[measured] squeeze %.2f: slope against the lift's gradient within %.2e; largest slope along u %.3f, v %.3f\n",
                squeeze, worst, largest_slope_u, largest_slope_v);
    EXPECT_LT(worst, 1e-3) << squeeze;
    // As laid, the ball meets most of the bumps' slope (0.1). Squeezed 20 times along u it rides
    // their crests that way (a real ball cannot enter bumps 0.13 mm apart) and along v meets
    // their crests' envelope, a |sin kv|, whose sharp troughs it bridges.
    if (squeeze < 1.0) {
      EXPECT_LT(largest_slope_u, 0.02);
      EXPECT_GT(largest_slope_v, 0.04);
    } else {
      EXPECT_GT(largest_slope_u, 0.07);
      EXPECT_GT(largest_slope_v, 0.07);
    }
  }
}

}  // namespace
}  // namespace thx::tex::test_ball_on_relief

namespace thx::tex::test_ball_on_relief {
namespace {

TEST(BallOnRelief, OnAHalfTheSearchMeetsThatSidesTexelsAloneAndTheHigherHalfIsTheWholeLift) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const TextureMap map = reliefOf(64, 32, [&](int i, int j) {
    return 2e-4 * std::sin(0.7 * i + 0.3 * j) * std::cos(0.45 * j) + 5e-5 * std::sin(2.1 * i * j);
  });
  const BallOnRelief reader(map, Address::Wrap);
  for (int k = 0; k < 200; ++k) {
    const TexCoord uv{unit(rng) * 3.0 - 1.0, unit(rng) * 3.0 - 1.0};
    const Eigen::Vector2d mpu(64 * kTexel * (k % 2 ? 1.0 : 0.1), 32 * kTexel);
    const double r = k % 3 ? 1e-3 : 4e-3;
    const BallOnRelief::Half half{k % 4 < 2 ? 0 : 1, k % 2 ? 1.0 : -1.0};
    const std::optional<BallOnRelief::Touch> on_half = reader.touchOnHalf(uv, mpu, r, false, half);
    ASSERT_TRUE(on_half) << k;  // a wrapped texture: every half holds texels
    const double brute = bruteForceLiftOnHalf(map, uv, mpu, r, half);
    ASSERT_GE(on_half->lift_m, brute - 1e-12) << k;
    // The refinement reads the bilinear surface on the half, which the texels up to one beyond
    // the line shape too.
    ASSERT_LE(on_half->lift_m, bruteForceLiftOnHalf(map, uv, mpu, r, half, 1.0) + 2e-5) << k;
    // The touch lies on its half: the centre from it points the other way along the axis.
    const double from_touch = half.axis == 0 ? on_half->normal.x() : on_half->normal.y();
    ASSERT_LE(from_touch * half.sign, 1e-12) << k;
    // Between the two halves of an axis every texel is met once: the higher is the whole lift,
    // up to the refinement, which on a half stops at the line through the centre.
    const std::optional<BallOnRelief::Touch> other = reader.touchOnHalf(uv, mpu, r, false, {half.axis, -half.sign});
    ASSERT_TRUE(other) << k;
    const double whole = reader.touch(uv, mpu, r).lift_m;
    ASSERT_LE(std::max(on_half->lift_m, other->lift_m), whole + 1e-12) << k;
    ASSERT_GE(std::max(on_half->lift_m, other->lift_m), bruteForceLift(map, uv, mpu, r) - 1e-12) << k;
  }
}

TEST(BallOnRelief, OverAVGroovesFloorEachHalfIsOneWall) {
  // V-grooves along v, 40 texels (4 mm) apart and 1 mm deep (walls at atan 0.5), under a 3 mm
  // ball, which fits in touching both walls: over the floor each half is one wall, its normal
  // the wall's and its lift the whole; a texel off the floor the half it moves towards lifts it
  // by the wall's slope, the other lowers it as much (to the relief's depth quantisation, 1e-4
  // of the slope here).
  const TextureMap map = reliefOf(80, 64, [](int i, int) { return -1e-3 * 2.0 * std::fabs(i / 40.0 - std::round(i / 40.0)); });
  const BallOnRelief reader(map, Address::Wrap);
  const Eigen::Vector2d mpu(80 * kTexel, 64 * kTexel);
  const double r = 3e-3, wall = 1.0 / std::sqrt(5.0);  // sin of the wall's angle
  const TexCoord floor{20.5 / 80.0, 0.3};
  const double whole = reader.touch(floor, mpu, r).lift_m;
  const auto left = reader.touchOnHalf(floor, mpu, r, false, {0, -1.0});
  const auto right = reader.touchOnHalf(floor, mpu, r, false, {0, 1.0});
  ASSERT_TRUE(left && right);
  EXPECT_NEAR(left->lift_m, whole, 1e-12);
  EXPECT_NEAR(right->lift_m, whole, 1e-12);
  EXPECT_NEAR(left->normal.x(), wall, 5e-4);  // the left wall pushes towards +u
  EXPECT_NEAR(right->normal.x(), -wall, 5e-4);
  EXPECT_NEAR(left->normal.x(), -right->normal.x(), 1e-5);
  const TexCoord off{21.5 / 80.0, 0.3};  // a texel (0.1 mm) towards +u
  const auto right_off = reader.touchOnHalf(off, mpu, r, false, {0, 1.0});
  const auto left_off = reader.touchOnHalf(off, mpu, r, false, {0, -1.0});
  ASSERT_TRUE(right_off && left_off);
  EXPECT_NEAR(right_off->lift_m - right->lift_m, 0.5 * kTexel, 1e-8);
  EXPECT_NEAR(left_off->lift_m - left->lift_m, -0.5 * kTexel, 1e-8);
  EXPECT_NEAR(reader.touch(off, mpu, r).lift_m, right_off->lift_m, 1e-12);
}

TEST(BallOnRelief, AClampedTexturesBorderLeavesTheHalfBeyondItEmpty) {
  const TextureMap map = reliefOf(16, 16, [](int, int) { return 0.0; });
  const BallOnRelief reader(map, Address::Clamp);
  const Eigen::Vector2d mpu(16 * kTexel, 16 * kTexel);
  // Beyond the last column's centre along +u: no texel on that half.
  EXPECT_FALSE(reader.touchOnHalf({0.999, 0.5}, mpu, 1e-3, false, {0, 1.0}));
  EXPECT_TRUE(reader.touchOnHalf({0.999, 0.5}, mpu, 1e-3, false, {0, -1.0}));
  EXPECT_TRUE(reader.touchOnHalf({0.5, 0.5}, mpu, 1e-3, false, {1, 1.0}));
}

}  // namespace
}  // namespace thx::tex::test_ball_on_relief
