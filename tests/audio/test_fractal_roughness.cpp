// Micro-level roughness (clients/audio/synthesis/fractal_roughness.hpp): a 1/f^beta profile read along the
// travelled distance, scaled by the normal force.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <complex>
#include <vector>

#include <unsupported/Eigen/FFT>

#include "clients/audio/synthesis/fractal_roughness.hpp"

namespace thx::audio::test_fractal_roughness {
namespace {

std::vector<double> powerSpectrum(const std::vector<double>& x) {
  Eigen::FFT<double> fft;
  std::vector<std::complex<double>> X;
  fft.fwd(X, x);
  std::vector<double> p(x.size() / 2 + 1);
  for (std::size_t k = 0; k < p.size(); ++k) p[k] = std::norm(X[k]);
  return p;
}

// Least-squares slope of log(power) against log(frequency index) over bins [lo, hi].
double logLogSlope(const std::vector<double>& power, std::size_t lo, std::size_t hi) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0, n = 0;
  for (std::size_t k = lo; k <= hi; ++k) {
    const double x = std::log(double(k)), y = std::log(power[k]);
    sx += x, sy += y, sxx += x * x, sxy += x * y, n += 1;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

double centroid(const std::vector<double>& power) {
  double num = 0, den = 0;
  for (std::size_t k = 1; k < power.size(); ++k) num += double(k) * power[k], den += power[k];
  return num / den;
}

// One second at 44.1 kHz read at `speed` with a constant normal force.
std::vector<double> readAt(const RoughnessProfile& p, double speed, double force_n) {
  std::vector<double> out(44100);
  microForce(p, 0.0, speed * 1.0, force_n, force_n, out);
  return out;
}

TEST(FractalRoughness, TableSpectrumFallsAsOneOverFToTheBeta) {
  for (double beta : {1.0, 2.0}) {
    RoughnessOptions o;
    o.beta = beta;
    o.length = 1u << 12;
    const RoughnessProfile p(o);
    const std::vector<double> t(p.table().begin(), p.table().end());
    double mean = 0, power = 0;
    for (double x : t) mean += x, power += x * x;
    EXPECT_NEAR(mean / double(t.size()), 0.0, 1e-12);
    EXPECT_NEAR(power / double(t.size()), 1.0, 1e-9);  // unit RMS
    // Three decades of spatial frequency.
    EXPECT_NEAR(logLogSlope(powerSpectrum(t), 2, 2048), -beta, 0.01) << "beta " << beta;
  }
}

TEST(FractalRoughness, ReadSignalKeepsTheSlopeAndDoublingTheSpeedDoublesItsFrequencies) {
  RoughnessOptions o;
  o.beta = 1.0;
  o.length = 1u << 12;  // 4096 x 10 um = 40.96 mm per period
  const RoughnessProfile p(o);
  const double period_m = 4096 * o.spacing_m;
  // One period per second: the spectrum's lines are 1 Hz apart, the finest roughness at 2048 Hz.
  const std::vector<double> slow = powerSpectrum(readAt(p, period_m, 1.0));
  const std::vector<double> fast = powerSpectrum(readAt(p, 2 * period_m, 1.0));
  // The temporal spectrum keeps the spatial slope (two decades, below the linear interpolation's
  // roll-off).
  const double slope = logLogSlope(slow, 3, 300);
  EXPECT_NEAR(slope, -1.0, 0.1);
  // Twice the speed: every line at twice the frequency, so the centroid doubles.
  const double ratio = centroid(fast) / centroid(slow);
  EXPECT_NEAR(ratio, 2.0, 0.1) << "centroids " << centroid(slow) << ", " << centroid(fast) << " Hz";
  std::printf("read slope %.4f; centroids %.1f and %.1f Hz, ratio %.4f\n", slope, centroid(slow), centroid(fast), ratio);
  // The same lines: the fast read's odd bins are empty (it repeats every half second).
  double odd = 0, all = 0;
  for (std::size_t k = 1; k < fast.size(); ++k) (k % 2 ? odd : all) += fast[k];
  EXPECT_LT(odd, 1e-12 * all);
}

TEST(FractalRoughness, LoudnessFollowsTheNormalForceAndZeroForceIsSilent) {
  const RoughnessProfile p(RoughnessOptions{});
  const std::vector<double> one = readAt(p, 0.05, 1.0), two = readAt(p, 0.05, 2.0), none = readAt(p, 0.05, 0.0);
  double rms = 0;
  for (std::size_t n = 0; n < one.size(); ++n) {
    EXPECT_EQ(two[n], 2.0 * one[n]);
    ASSERT_EQ(none[n], 0.0);
    rms += one[n] * one[n];
  }
  // Amplitude x force x a unit-RMS profile (1 s reads 5 cm of a 33 cm period: near, not exactly, 1).
  EXPECT_NEAR(std::sqrt(rms / double(one.size())), 0.03, 0.015);
}

TEST(FractalRoughness, ReadByDistanceNotTime) {
  const RoughnessProfile p(RoughnessOptions{});
  // The same distance in one segment or in two gives the same values at the same places.
  std::vector<double> whole(200), halves(200);
  microForce(p, 0.0, 2e-3, 1.0, 1.0, whole);
  microForce(p, 0.0, 1e-3, 1.0, 1.0, std::span<double>(halves).first(100));
  microForce(p, 1e-3, 2e-3, 1.0, 1.0, std::span<double>(halves).subspan(100));
  for (std::size_t n = 0; n < whole.size(); ++n) EXPECT_NEAR(whole[n], halves[n], 1e-12);
  // Periodic, interpolated between entries.
  EXPECT_NEAR(p.at(0.0), p.at(double(p.table().size()) * 1e-5), 1e-12);
  EXPECT_NEAR(p.at(0.5e-5), 0.5 * (p.table()[0] + p.table()[1]), 1e-12);
}

TEST(FractalRoughness, FastContactsReadABandLimitedLevelInsteadOfAliasing) {
  RoughnessOptions o;
  o.length = 1u << 12;
  const RoughnessProfile p(o);
  ASSERT_EQ(p.levels(), 11u);  // 4096 down to 4 entries
  // Level L keeps the bins k <= 2048 / 2^L: for beta = 1 its power is the share of sum 1/k.
  auto share = [](std::size_t top) {
    double part = 0, all = 0;
    for (std::size_t k = 1; k <= 2048; ++k) (k <= top ? part : all) += 1.0 / double(k);
    return part / (part + all);
  };
  for (std::size_t level : {1u, 3u}) {
    double power = 0;
    for (double x : p.table(level)) power += x * x;
    EXPECT_NEAR(power / double(p.table(level).size()), share(2048u >> level), 0.01) << "level " << level;
    // The same profile without its finest part: correlated with level 0 at the same places as a
    // part with the whole, sqrt(share).
    double ab = 0, aa = 0, bb = 0;
    for (std::size_t i = 0; i < p.table(level).size(); ++i) {
      const double x = p.table(level)[i], y = p.table(0)[i << level];
      ab += x * y, aa += x * x, bb += y * y;
    }
    EXPECT_NEAR(ab / std::sqrt(aa * bb), std::sqrt(share(2048u >> level)), 0.03) << "level " << level;
  }
  // 8 entries per sample: level 3 is read, with 3/4 of the power (the rest is finer than two
  // samples); reading level 0 there would fold all of it back (RMS near 1).
  std::vector<double> fast(4096);
  microForce(p, 0.0, 8 * 4096 * o.spacing_m, 1.0, 1.0, fast);
  double power = 0, aliased = 0;
  for (std::size_t n = 0; n < fast.size(); ++n) {
    power += fast[n] * fast[n];
    const double x = p.at(8.0 * double(n) * o.spacing_m, 0);
    aliased += x * x;
  }
  const double a2 = o.amplitude * o.amplitude * double(fast.size());
  EXPECT_NEAR(power / a2, share(256), 0.02);
  EXPECT_NEAR(aliased / double(fast.size()), 1.0, 0.05);
  std::printf("8 entries per sample: power %.4f (share %.4f), level 0 read %.4f\n", power / a2, share(256),
              aliased / double(fast.size()));
  // Slow contacts read level 0, unchanged.
  std::vector<double> slow(100);
  microForce(p, 0.0, 100 * o.spacing_m, 1.0, 1.0, slow);
  for (std::size_t n = 0; n < slow.size(); ++n)
    EXPECT_NEAR(slow[n], o.amplitude * p.at(double(n) * o.spacing_m, 0), 1e-15);
}

TEST(FractalRoughness, SameSeedSameProfileOtherSeedAnother) {
  RoughnessOptions o;
  const RoughnessProfile a(o), b(o);
  o.seed = 2;
  const RoughnessProfile c(o);
  EXPECT_TRUE(std::equal(a.table().begin(), a.table().end(), b.table().begin()));
  EXPECT_FALSE(std::equal(a.table().begin(), a.table().end(), c.table().begin()));
}

TEST(FractalRoughness, BadOptionsAreRefused) {
  RoughnessOptions o;
  o.length = 1000;
  EXPECT_THROW(RoughnessProfile{o}, std::logic_error);
  o = {};
  o.spacing_m = 0;
  EXPECT_THROW(RoughnessProfile{o}, std::logic_error);
  o = {};
  o.beta = -1;
  EXPECT_THROW(RoughnessProfile{o}, std::logic_error);
}

}  // namespace
}  // namespace thx::audio::test_fractal_roughness
