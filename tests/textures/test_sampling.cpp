// Sampling convention: texel centres, nearest/bilinear, wrap/clamp, (u,v) <-> texel, plane mapping.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "textures/plane_mapping.hpp"
#include "textures/sampling.hpp"

namespace test_sampling {

using namespace thx::tex;

namespace {

// A relief map whose depth code is linear in (i, j): code = 1000 + 300 i + 200 j.
TextureMap linearDepthMap(int w, int h) {
  TextureMap map(w, h, Representation::Relief, 0.002);
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) map.setDepthCode(i, j, std::uint16_t(1000 + 300 * i + 200 * j));
  return map;
}

double linearDepthAt(double s, double t) { return (1000 + 300 * s + 200 * t) * 0.002 / 65535.0; }

// Distinct normals per texel so a wrong texel is always detected.
TextureMap distinctNormalMap(int w, int h) {
  TextureMap map(w, h, Representation::Normal);
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) map.setNormal(i, j, Eigen::Vector3f(0.05f * float(i) - 0.2f, 0.04f * float(j) - 0.3f, 1.0f));
  return map;
}

}  // namespace

TEST(Sampling, TexelCentreAndTexelOfAreInverse) {
  const TextureMap map = distinctNormalMap(7, 5);
  for (int j = 0; j < 5; ++j) {
    for (int i = 0; i < 7; ++i) {
      const TexCoord c = texelCentre(map, {i, j});
      EXPECT_EQ(texelOf(map, c, Address::Clamp), (TexelIndex{i, j}));
      EXPECT_EQ(texelOf(map, c, Address::Wrap), (TexelIndex{i, j}));
    }
  }
  // Row 0 is the top of the image: v close to 1.
  EXPECT_EQ(texelOf(map, {0.01, 0.99}, Address::Clamp), (TexelIndex{0, 0}));
  EXPECT_EQ(texelOf(map, {0.99, 0.01}, Address::Clamp), (TexelIndex{6, 4}));
}

TEST(Sampling, NearestReturnsContainingTexel) {
  const TextureMap map = distinctNormalMap(8, 8);
  const SampleOptions nearest{Filter::Nearest, Address::Clamp};
  // Just inside texel (2, 5)'s borders.
  const double u_lo = 2.0 / 8 + 1e-9, u_hi = 3.0 / 8 - 1e-9;
  const double v_lo = 1.0 - 6.0 / 8 + 1e-9, v_hi = 1.0 - 5.0 / 8 - 1e-9;
  for (double u : {u_lo, u_hi})
    for (double v : {v_lo, v_hi}) EXPECT_TRUE(sampleNormal(map, {u, v}, nearest).isApprox(map.normal(2, 5)));
}

TEST(Sampling, BilinearIsExactOnLinearDepth) {
  const TextureMap map = linearDepthMap(16, 12);
  const SampleOptions bilinear{Filter::Bilinear, Address::Clamp};
  std::mt19937 rng(7);
  // Stay between the outermost texel centres, where clamping does not apply.
  std::uniform_real_distribution<double> us(0.5 / 16, 1 - 0.5 / 16), vs(0.5 / 12, 1 - 0.5 / 12);
  for (int k = 0; k < 1000; ++k) {
    const TexCoord uv{us(rng), vs(rng)};
    const double expected = linearDepthAt(texelS(map, uv.u), texelT(map, uv.v));
    // float accumulation: relative 1e-6 of the 2 mm maximum depth.
    EXPECT_NEAR(sampleDepth(map, uv, bilinear), expected, 2e-9) << uv.u << " " << uv.v;
  }
}

TEST(Sampling, BilinearHitsTexelValuesAtCentresAndAveragesBetween) {
  const TextureMap map = distinctNormalMap(6, 6);
  const SampleOptions bilinear{Filter::Bilinear, Address::Clamp};
  // Stored normals are snorm16 (length 1 +- 3e-5); sampling renormalises, hence 5e-5.
  for (int j = 0; j < 6; ++j)
    for (int i = 0; i < 6; ++i)
      EXPECT_LT((sampleNormal(map, texelCentre(map, {i, j}), bilinear) - map.normal(i, j)).norm(), 5e-5f);
  const TexCoord a = texelCentre(map, {2, 3}), b = texelCentre(map, {3, 3});
  const Eigen::Vector3f mid = sampleNormal(map, {(a.u + b.u) / 2, a.v}, bilinear);
  const Eigen::Vector3f expected = (map.normal(2, 3) + map.normal(3, 3)).normalized();
  EXPECT_LT((mid - expected).norm(), 1e-5f);
  EXPECT_NEAR(mid.norm(), 1.0f, 1e-6f);  // renormalised
}

TEST(Sampling, WrapRepeatsAndBlendsAcrossTheSeam) {
  const TextureMap map = distinctNormalMap(8, 4);
  const SampleOptions wrap{Filter::Bilinear, Address::Wrap};
  for (double u : {0.013, 0.37, 0.5, 0.999}) {
    const Eigen::Vector3f n = sampleNormal(map, {u, 0.3}, wrap);
    EXPECT_LT((sampleNormal(map, {u + 1.0, 0.3}, wrap) - n).norm(), 1e-5f);
    EXPECT_LT((sampleNormal(map, {u - 3.0, 0.3 + 2.0}, wrap) - n).norm(), 1e-5f);
  }
  // u = 0 lies halfway between the centres of the last and first columns.
  const TexCoord last = texelCentre(map, {7, 1});
  const Eigen::Vector3f seam = sampleNormal(map, {0.0, last.v}, wrap);
  EXPECT_LT((seam - (map.normal(7, 1) + map.normal(0, 1)).normalized()).norm(), 1e-5f);
}

TEST(Sampling, ClampExtendsEdgeTexels) {
  const TextureMap map = linearDepthMap(8, 8);
  const SampleOptions clamp{Filter::Bilinear, Address::Clamp};
  EXPECT_FLOAT_EQ(sampleDepth(map, {-5.0, 0.5 / 8}, clamp), map.depth(0, 7));
  EXPECT_FLOAT_EQ(sampleDepth(map, {0.01, 0.999}, clamp), map.depth(0, 0));
  EXPECT_FLOAT_EQ(sampleDepth(map, {7.0, -2.0}, clamp), map.depth(7, 7));
  EXPECT_EQ(texelOf(map, {1e300, -1e300}, Address::Clamp), (TexelIndex{7, 7}));
}

TEST(Sampling, NonFiniteCoordinatesSampleAsFlatPlane) {
  const TextureMap map = linearDepthMap(4, 4);
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  for (Filter f : {Filter::Nearest, Filter::Bilinear}) {
    for (Address a : {Address::Wrap, Address::Clamp}) {
      const Sample s = sample(map, {nan, 0.5}, {f, a});
      EXPECT_EQ(s.normal, Eigen::Vector3f(0, 0, 1));
      EXPECT_EQ(s.depth, 0.0f);
      EXPECT_EQ(sample(map, {0.5, inf}, {f, a}).depth, 0.0f);
    }
  }
  // Huge but finite coordinates wrap without overflow.
  EXPECT_NO_FATAL_FAILURE(sample(map, {1e18, -1e18}, {Filter::Bilinear, Address::Wrap}));
}

TEST(Sampling, DepthAloneIsTheFullSamplesDepthToTheBit) {
  // sampleDepth skips the normal (the textured ball's raster reads it at every texel).
  const TextureMap relief = linearDepthMap(9, 6), normals = distinctNormalMap(7, 5);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> uv(-1.5, 2.5);
  for (const Filter filter : {Filter::Nearest, Filter::Bilinear})
    for (const Address address : {Address::Wrap, Address::Clamp})
      for (int k = 0; k < 2000; ++k) {
        const TexCoord at{uv(rng), uv(rng)};
        const SampleOptions options{filter, address};
        EXPECT_EQ(sampleDepth(relief, at, options), sample(relief, at, options).depth) << at.u << " " << at.v;
        EXPECT_EQ(sampleDepth(normals, at, options), sample(normals, at, options).depth);
      }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(sampleDepth(relief, {nan, 0.5}, {}), 0.0f);
}

// A SamplePlace reads its depth and normal in two parts (the physics reads a textured box's
// normal only at its candidates), each as sample() reads it.
TEST(Sampling, APlaceReadsTheSamplesDepthAndNormalToTheBit) {
  TextureMap relief = linearDepthMap(9, 6);
  for (int j = 0; j < relief.height(); ++j)
    for (int i = 0; i < relief.width(); ++i)
      relief.setNormal(i, j, Eigen::Vector3f(0.05f * float(i) - 0.2f, 0.04f * float(j) - 0.3f, 1.0f));
  const TextureMap normals = distinctNormalMap(7, 5);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> uv(-1.5, 2.5);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<TexCoord> at = {{nan, 0.5}, {0.5, std::numeric_limits<double>::infinity()}, {0.0, 0.0}, {1.0, 1.0}};
  for (int k = 0; k < 2000; ++k) at.push_back({uv(rng), uv(rng)});
  for (const Filter filter : {Filter::Nearest, Filter::Bilinear})
    for (const Address address : {Address::Wrap, Address::Clamp})
      for (const TextureMap* map : {static_cast<const TextureMap*>(&relief), &normals})
        for (const TexCoord c : at) {
          const SampleOptions options{filter, address};
          const SamplePlace place(*map, c, options);
          const Sample whole = sample(*map, c, options);
          EXPECT_EQ(place.depth(), whole.depth) << c.u << " " << c.v;
          EXPECT_EQ(place.normal(), whole.normal) << c.u << " " << c.v;
        }
  // A place made without a map reads as the flat plane, as a non-finite uv does.
  EXPECT_EQ(SamplePlace().depth(), 0.0f);
  EXPECT_EQ(SamplePlace().normal(), Eigen::Vector3f(0.0f, 0.0f, 1.0f));
}

// A bilinear sample reads the four texels resolveIndex names round the reduced coordinate, with the
// weights of its fractions, to the bit: the sampler resolves them without a division
// (sampling.cpp), which must agree with resolveIndex on every index a reduced coordinate reaches,
// at the seam of a wrapped map (u = 0 and u just below 0, which reduces to 1) and past a clamped
// map's edges.
TEST(Sampling, BilinearReadsTheTexelsResolveIndexNames) {
  const TextureMap relief = linearDepthMap(9, 6);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> uv(-2.5, 3.5);
  std::vector<TexCoord> at = {{0.0, 0.0}, {1.0, 1.0}, {-1e-20, 0.5}, {0.5, -1e-20}, {1.0 - 1e-17, 0.5},
                              {0.5 / 9.0, 0.5 / 6.0}, {-1.0, 2.0}, {2.0, -1.0}, {-0.0, 0.999999999}};
  for (int k = 0; k < 4000; ++k) at.push_back({uv(rng), uv(rng)});
  for (const Address address : {Address::Wrap, Address::Clamp}) {
    const auto reduce = [&](double u) {
      return address == Address::Wrap ? u - std::floor(u) : std::fmin(2.0, std::fmax(-1.0, u));
    };
    for (const TexCoord c : at) {
      const double s = texelS(relief, reduce(c.u)), t = texelT(relief, reduce(c.v));
      const double s0 = std::floor(s), t0 = std::floor(t);
      const float fs = float(s - s0), ft = float(t - t0);
      const int i0 = resolveIndex((long long)s0, relief.width(), address), i1 = resolveIndex((long long)s0 + 1, relief.width(), address);
      const int j0 = resolveIndex((long long)t0, relief.height(), address), j1 = resolveIndex((long long)t0 + 1, relief.height(), address);
      const float expected = (1 - fs) * (1 - ft) * relief.depth(i0, j0) + fs * (1 - ft) * relief.depth(i1, j0) +
                             (1 - fs) * ft * relief.depth(i0, j1) + fs * ft * relief.depth(i1, j1);
      EXPECT_EQ(sampleDepth(relief, c, {Filter::Bilinear, address}), expected) << c.u << " " << c.v;
    }
  }
}

TEST(PlaneMapping, UvAndWorldRoundTrip) {
  PlaneMapping m;
  m.size_m = {0.3, 0.2};
  m.plane_to_world = Eigen::Translation3d(0.1, -0.2, 0.05) * Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized());
  const TexCoord corner = m.uvOfLocal({-0.15, -0.1});
  EXPECT_DOUBLE_EQ(corner.u, 0.0);
  EXPECT_DOUBLE_EQ(corner.v, 0.0);
  const TexCoord centre = m.uvOfLocal({0.0, 0.0});
  EXPECT_DOUBLE_EQ(centre.u, 0.5);
  const Eigen::Vector2d xy = m.localOfUv({0.25, 0.8});
  EXPECT_NEAR(xy.x(), -0.075, 1e-15);
  EXPECT_NEAR(xy.y(), 0.06, 1e-15);
  const Eigen::Vector3d p(0.4, 0.1, -0.3);
  EXPECT_LT((m.toWorld(m.toLocal(p)) - p).norm(), 1e-15);
  EXPECT_NEAR(m.geometricNormalWorld().dot(m.directionToWorld({1, 0, 0})), 0.0, 1e-15);
  EXPECT_LT((m.directionToLocal(m.geometricNormalWorld()) - Eigen::Vector3d(0, 0, 1)).norm(), 1e-15);
  const TextureMap map(60, 40, Representation::Normal);
  EXPECT_DOUBLE_EQ(m.texelSize(map).x(), 0.005);
  EXPECT_DOUBLE_EQ(m.texelSize(map).y(), 0.005);
}

}  // namespace test_sampling
