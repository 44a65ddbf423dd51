// Height field -> normals and relief maps (textures/height_normals.hpp).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <limits>

#include "textures/height_normals.hpp"
#include "textures/texture_error.hpp"

namespace test_height_normals {

using namespace thx::tex;

namespace {

constexpr double kPi = 3.14159265358979323846;

double angleBetween(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

// Plane-local centre of texel (i, j) of an n x n texture of side `extent` centred on the origin.
Eigen::Vector2d centre(int i, int j, int n, double extent) {
  return {((i + 0.5) / n - 0.5) * extent, (0.5 - (j + 0.5) / n) * extent};
}

// h = A sin(kx) sin(ky): 10 whole periods across the extent, so Address::Wrap is exact.
struct Sinusoid {
  double amplitude = 0.001;  // m: steepest slope 2*pi*A/period = 0.31 (17.4 deg)
  double period = 0.02;      // m
  double h(const Eigen::Vector2d& p) const {
    const double k = 2 * kPi / period;
    return amplitude * std::sin(k * p.x()) * std::sin(k * p.y());
  }
};

// Largest angle (rad) between the central-difference normals of the sampled sinusoid and the
// analytic normals at the texel centres. Plain doubles: this runs on 1.4 M texels under ASan too.
double maxSinusoidError(int n) {
  const double extent = 0.2;
  const Sinusoid s;
  HeightField field(n, n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) field.at(i, j) = s.h(centre(i, j, n, extent));
  const std::vector<Eigen::Vector3f> normals =
      normalsFromHeight(field, Eigen::Vector2d(extent / n, extent / n), Address::Wrap);
  const double k = 2 * kPi / s.period, ak = s.amplitude * k;
  double worst_cos = 1.0;
  for (int j = 0; j < n; ++j) {
    const double y = (0.5 - (j + 0.5) / n) * extent, sy = std::sin(k * y), cy = std::cos(k * y);
    for (int i = 0; i < n; ++i) {
      const double x = ((i + 0.5) / n - 0.5) * extent, sx = std::sin(k * x), cx = std::cos(k * x);
      const double ex = -ak * cx * sy, ey = -ak * sx * cy;  // analytic normal, unnormalised (z = 1)
      const Eigen::Vector3f& g = normals[std::size_t(j) * std::size_t(n) + std::size_t(i)];
      const double c = (g.x() * ex + g.y() * ey + g.z()) / std::sqrt(ex * ex + ey * ey + 1.0) /
                       std::sqrt(double(g.x()) * g.x() + double(g.y()) * g.y() + double(g.z()) * g.z());
      worst_cos = std::min(worst_cos, c);
    }
  }
  // acos loses precision near 1: recover the angle from 1 - cos = 2 sin^2(a/2).
  return 2 * std::asin(std::sqrt(std::max(0.0, (1 - worst_cos) / 2)));
}

}  // namespace

// Central differences are second-order: halving the texel should quarter the error. The slope
// error of a sinusoid of wavenumber k is (k d)^2 / 6 of its slope, so the worst angular error is
// about 0.31 * (k d)^2 / 6 / (1 + 0.31^2) rad (k = 2 pi / 0.02 m, d = 0.2 m / n).
TEST(HeightNormals, SinusoidErrorFallsQuadratically) {
  const int sizes[] = {128, 256, 512, 1024};
  double errors[4];
  for (int k = 0; k < 4; ++k) {
    errors[k] = maxSinusoidError(sizes[k]);
    const double d = 0.2 / sizes[k], kd = 2 * kPi / 0.02 * d;
    const double predicted = 0.314 * kd * kd / 6.0 / (1 + 0.314 * 0.314);
    std::printf("[ height->normal ] sinusoid A=1 mm period=20 mm extent=0.2 m, %4d^2 texels (%.4f mm): "
                "max angular error %.3e rad = %.5f deg (predicted ~%.3e rad)\n",
                sizes[k], d * 1e3, errors[k], errors[k] * 180 / kPi, predicted);
    EXPECT_LT(errors[k], 1.2 * predicted) << sizes[k];
  }
  for (int k = 0; k + 1 < 4; ++k) {
    const double ratio = errors[k] / errors[k + 1];
    std::printf("[ height->normal ] error ratio %d -> %d: %.3f (quadratic: 4)\n", sizes[k], sizes[k + 1], ratio);
    EXPECT_GT(ratio, 3.6);
    EXPECT_LT(ratio, 4.4);
  }
  // 1024^2 over 0.2 m (0.195 mm texels, 102 texels per period): below 2e-4 rad (0.0115 deg).
  EXPECT_LT(errors[3], 2e-4);
}

// The whole-map routine and the per-texel one apply the same rule.
TEST(HeightNormals, MapAndTexelRoutinesAgree) {
  HeightField field(7, 5);
  for (int j = 0; j < 5; ++j)
    for (int i = 0; i < 7; ++i) field.at(i, j) = 0.001 * std::sin(1.3 * i + 0.7 * j * j);
  const Eigen::Vector2d texel(0.001, 0.0015);
  for (Address address : {Address::Wrap, Address::Clamp}) {
    const std::vector<Eigen::Vector3f> all = normalsFromHeight(field, texel, address);
    for (int j = 0; j < 5; ++j)
      for (int i = 0; i < 7; ++i)
        EXPECT_LT((all[std::size_t(j * 7 + i)].cast<double>() - heightNormalAt(field, i, j, texel, address)).norm(), 1e-6);
  }
}

// A plane is differenced exactly, including the one-sided differences at clamped borders.
TEST(HeightNormals, ClampIsExactForAPlaneEverywhere) {
  const int w = 9, h = 6;
  const Eigen::Vector2d texel(0.001, 0.002);
  const double gx = 0.3, gy = -0.2;  // dh/dx, dh/dy
  HeightField field(w, h);
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) field.at(i, j) = 0.01 + gx * i * texel.x() + gy * (h - 1 - j) * texel.y();
  const Eigen::Vector3d expected = Eigen::Vector3d(-gx, -gy, 1).normalized();
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i)
      EXPECT_LT(angleBetween(heightNormalAt(field, i, j, texel, Address::Clamp), expected), 1e-12) << i << "," << j;
}

// +y is image up: heights that rise towards row 0 have dh/dy > 0, so the normal leans to -y.
TEST(HeightNormals, RowZeroIsTheTopOfTheImage) {
  HeightField field(4, 4);
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) field.at(i, j) = 0.001 * (3 - j);  // highest on row 0
  const Eigen::Vector3d n = heightNormalAt(field, 1, 1, Eigen::Vector2d(0.001, 0.001), Address::Clamp);
  EXPECT_NEAR(n.x(), 0.0, 1e-12);
  EXPECT_LT(n.y(), -0.5);  // slope 1: n = (0, -1, 1) / sqrt 2
  EXPECT_NEAR(n.y(), -std::sqrt(0.5), 1e-12);
}

// Wrap differences across the border with the opposite edge; clamp does not.
TEST(HeightNormals, WrapUsesTheOppositeEdge) {
  HeightField field(4, 3);
  for (int j = 0; j < 3; ++j) {
    field.at(0, j) = 0.0;
    field.at(1, j) = 0.0;
    field.at(2, j) = 0.0;
    field.at(3, j) = 0.002;  // a step at the right edge
  }
  const Eigen::Vector2d texel(0.001, 0.001);
  // Column 0: wrap sees (h(1) - h(3)) / 2d = -1, clamp sees (h(1) - h(0)) / d = 0.
  const Eigen::Vector3d wrap = heightNormalAt(field, 0, 1, texel, Address::Wrap);
  const Eigen::Vector3d clamp = heightNormalAt(field, 0, 1, texel, Address::Clamp);
  EXPECT_NEAR(wrap.x(), std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(clamp.x(), 0.0, 1e-12);
}

TEST(HeightNormals, ReliefDepthIsHighestMinusHeight) {
  HeightField field(3, 2);
  field.heights_m = {0.001, 0.002, 0.004, 0.0, 0.003, 0.001};
  ReliefFromHeightOptions options;
  options.texel_m = {0.0005, 0.0005};
  const TextureMap map = reliefFromHeight(field, options);
  ASSERT_TRUE(map.isRelief());
  EXPECT_DOUBLE_EQ(map.maxDepth(), 0.004);
  const double q = 0.004 / 65535;  // one depth code
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(map.depth(i, j), 0.004 - field.at(i, j), q) << i << "," << j;
  EXPECT_EQ(map.meta().kind, "height");
  EXPECT_DOUBLE_EQ(map.meta().extent_x_m, 0.0015);
  EXPECT_DOUBLE_EQ(map.meta().extent_y_m, 0.001);
}

TEST(HeightNormals, FlatFieldGetsATinyPositiveDepthRange) {
  ReliefFromHeightOptions options;
  options.texel_m = {0.001, 0.001};
  const TextureMap map = reliefFromHeight(HeightField(5, 5, 0.3), options);
  EXPECT_EQ(map.maxDepth(), kFlatReliefDepth_m);
  for (int j = 0; j < 5; ++j)
    for (int i = 0; i < 5; ++i) {
      EXPECT_EQ(map.depthCode(i, j), 0);
      EXPECT_EQ(map.normal(i, j), Eigen::Vector3f(0, 0, 1));
    }
}

TEST(HeightNormals, NormalRepresentationHasNoDepth) {
  HeightField field(4, 4);
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) field.at(i, j) = 0.001 * i;
  ReliefFromHeightOptions options;
  options.texel_m = {0.001, 0.001};
  options.representation = Representation::Normal;
  const TextureMap map = reliefFromHeight(field, options);
  EXPECT_FALSE(map.isRelief());
  EXPECT_EQ(map.maxDepth(), 0.0);
  EXPECT_NEAR(map.normal(1, 1).x(), -std::sqrt(0.5), 1e-4);
}

TEST(HeightNormals, NonFiniteHeightsNameTheFirstSampleAndTheCount) {
  HeightField field(5, 4, 0.0);
  field.at(3, 1) = std::numeric_limits<double>::quiet_NaN();
  field.at(0, 2) = std::numeric_limits<double>::infinity();
  ReliefFromHeightOptions options;
  options.texel_m = {0.001, 0.001};
  options.source = "bumps.png";
  try {
    reliefFromHeight(field, options);
    FAIL() << "no error";
  } catch (const TextureError& e) {
    const std::string m = e.what();
    EXPECT_EQ(e.source(), "bumps.png");
    EXPECT_NE(m.find("(3, 1)"), std::string::npos) << m;
    EXPECT_NE(m.find("2 non-finite"), std::string::npos) << m;
  }
}

TEST(HeightNormals, BadSizesAndTexelSizesAreRefused) {
  ReliefFromHeightOptions options;
  options.texel_m = {0.001, 0.001};
  EXPECT_THROW(reliefFromHeight(HeightField(1, 4), options), TextureError);
  HeightField wrong_count(4, 4);
  wrong_count.heights_m.pop_back();
  EXPECT_THROW(reliefFromHeight(wrong_count, options), TextureError);
  options.texel_m = {0.001, -0.001};
  try {
    reliefFromHeight(HeightField(4, 4), options);
    FAIL() << "no error";
  } catch (const TextureError& e) {
    EXPECT_NE(std::string(e.what()).find("texel size along y"), std::string::npos) << e.what();
  }
}

}  // namespace test_height_normals
