// Normals -> heights (textures/height_from_normals.hpp): a map made from heights gives its heights
// back, wrapping or clamped at its borders, and bad input is refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>

#include "textures/height_from_normals.hpp"
#include "textures/height_normals.hpp"
#include "textures/texture_error.hpp"

namespace test_height_from_normals {

using namespace thx::tex;

namespace {

constexpr double kPi = 3.14159265358979323846;

HeightField sampled(int w, int h, const std::function<double(int, int)>& height) {
  HeightField f(w, h);
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) f.at(i, j) = height(i, j);
  return f;
}

// A normal map of the field's central differences (height_normals.hpp).
TextureMap normalsOf(const HeightField& field, const Eigen::Vector2d& texel, Address address) {
  ReliefFromHeightOptions o;
  o.texel_m = texel;
  o.address = address;
  o.representation = Representation::Normal;
  return reliefFromHeight(field, o);
}

// The largest difference between two fields, each less its mean, over the largest height.
double relativeError(const HeightField& a, const HeightField& b) {
  double mean_a = 0.0, mean_b = 0.0, peak = 0.0, worst = 0.0;
  for (std::size_t k = 0; k < a.heights_m.size(); ++k) mean_a += a.heights_m[k], mean_b += b.heights_m[k];
  mean_a /= double(a.heights_m.size()), mean_b /= double(b.heights_m.size());
  for (std::size_t k = 0; k < a.heights_m.size(); ++k) {
    peak = std::max(peak, std::fabs(a.heights_m[k] - mean_a));
    worst = std::max(worst, std::fabs((a.heights_m[k] - mean_a) - (b.heights_m[k] - mean_b)));
  }
  return worst / peak;
}

TEST(HeightsFromNormals, APeriodicReliefsNormalsGiveItsHeightsBack) {
  // Sine bumps in both directions plus a finer ripple along x, 96 x 64 texels of 0.1 x 0.15 mm.
  const Eigen::Vector2d texel(1e-4, 1.5e-4);
  const HeightField field = sampled(96, 64, [](int i, int j) {
    return 40e-6 * std::sin(2 * kPi * i / 24.0) * std::cos(2 * kPi * j / 16.0) + 5e-6 * std::sin(2 * kPi * i / 8.0);
  });
  const TextureMap normals = normalsOf(field, texel, Address::Wrap);
  const IntegratedNormals back = heightsFromNormals(normals, texel, Address::Wrap);
  const double error = relativeError(field, back.heights);
  std::printf("[measured] periodic bumps: heights back within %.2g of the largest\n", error);
  // What is left is the normals' 16-bit rounding.
  EXPECT_LT(error, 1e-3);
  EXPECT_LT(back.mean_slope.norm(), 1e-6);  // bumps: level on average
}

TEST(HeightsFromNormals, AClampedReliefIsReadEvenAcrossItsBorders) {
  // A dome that does not wrap: its slopes at the left and right borders differ.
  const Eigen::Vector2d texel(2e-4, 2e-4);
  const HeightField field = sampled(64, 64, [](int i, int j) {
    const double x = (i - 20.0) / 64.0, y = (j - 40.0) / 64.0;
    return 100e-6 * std::exp(-(x * x + y * y) / 0.05);
  });
  const TextureMap normals = normalsOf(field, texel, Address::Clamp);
  const double wrapped = relativeError(field, heightsFromNormals(normals, texel, Address::Wrap).heights);
  const double clamped = relativeError(field, heightsFromNormals(normals, texel, Address::Clamp).heights);
  std::printf("[measured] clamped dome: heights back within %.2g of the largest (read as wrapping: %.2g)\n", clamped, wrapped);
  EXPECT_LT(clamped, 0.03);
  EXPECT_GT(wrapped, 3.0 * clamped);  // the mirror is what makes a clamped map integrate
}

TEST(HeightsFromNormals, AUniformTiltIsAllMeanSlopeWrappingAndARampClamped) {
  // dh/dx = 0.2, dh/dy = -0.1 everywhere.
  const Eigen::Vector2d texel(1e-4, 1e-4);
  const HeightField ramp = sampled(32, 32, [&](int i, int j) { return 0.2 * i * texel.x() + 0.1 * j * texel.y(); });
  const TextureMap tilted = normalsOf(ramp, texel, Address::Clamp);
  const IntegratedNormals wrapped = heightsFromNormals(tilted, texel, Address::Wrap);
  EXPECT_NEAR(wrapped.mean_slope.x(), 0.2, 1e-4);
  EXPECT_NEAR(wrapped.mean_slope.y(), -0.1, 1e-4);
  for (double v : wrapped.heights.heights_m) EXPECT_NEAR(v, 0.0, 1e-9);
  const IntegratedNormals clamped = heightsFromNormals(tilted, texel, Address::Clamp);
  EXPECT_EQ(clamped.mean_slope, Eigen::Vector2d::Zero());
  // Measured 3.2 % of the ramp's rise: at the borders the map's one-sided differences meet the
  // mirror's halved central ones.
  EXPECT_LT(relativeError(ramp, clamped.heights), 0.05);
}

TEST(HeightsFromNormals, AFlatMapIsFlatAndABadTexelSizeIsRefused) {
  const TextureMap flat(32, 32, Representation::Normal);
  const HeightField h = heightsFromNormals(flat, {1e-4, 1e-4}, Address::Wrap).heights;
  for (double v : h.heights_m) EXPECT_NEAR(v, 0.0, 1e-15);
  EXPECT_THROW(heightsFromNormals(flat, {0.0, 1e-4}, Address::Wrap), TextureError);
  EXPECT_THROW(heightsFromNormals(flat, {1e-4, std::nan("")}, Address::Wrap), TextureError);
}

}  // namespace
}  // namespace test_height_from_normals
