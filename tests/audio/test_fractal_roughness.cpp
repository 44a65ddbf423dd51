// Micro-level roughness (clients/audio/fractal_roughness.hpp): a 1/f^beta profile read along the
// travelled distance, scaled by the normal force.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <complex>
#include <vector>

#include <unsupported/Eigen/FFT>

#include "clients/audio/fractal_roughness.hpp"

namespace thx::audio {
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
  EXPECT_THROW(RoughnessProfile{o}, std::invalid_argument);
  o = {};
  o.spacing_m = 0;
  EXPECT_THROW(RoughnessProfile{o}, std::invalid_argument);
  o = {};
  o.beta = -1;
  EXPECT_THROW(RoughnessProfile{o}, std::invalid_argument);
}

}  // namespace
}  // namespace thx::audio
