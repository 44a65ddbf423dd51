#include "clients/audio/synthesis/fractal_roughness.hpp"

#include <cmath>
#include <complex>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string>

#include <unsupported/Eigen/FFT>

namespace thx::audio {

RoughnessProfile::RoughnessProfile(const RoughnessOptions& o) : options_(o) {
  const std::size_t n = o.length;
  if (n < 4 || (n & (n - 1)) != 0)
    throw std::logic_error("roughness length: expected a power of two >= 4, got " + std::to_string(n));
  if (!(o.spacing_m > 0.0))
    throw std::logic_error("roughness spacing: expected > 0 m, got " + std::to_string(o.spacing_m));
  if (!(o.beta >= 0.0 && o.beta <= 4.0))
    throw std::logic_error("roughness beta: expected a number in [0, 4], got " + std::to_string(o.beta));

  // Exact amplitudes k^(-beta/2) with random phases: the slope is exactly -beta, the realisation
  // set by the seed. mt19937_64's output sequence is fixed by the standard (unlike the
  // distributions), so the phases are the same with every standard library.
  std::mt19937_64 rng(o.seed);
  std::vector<std::complex<double>> spectrum(n, {0.0, 0.0});
  for (std::size_t k = 1; k <= n / 2; ++k) {
    const double phase = 2.0 * std::numbers::pi * double(rng() >> 11) * 0x1.0p-53;
    const double a = std::pow(double(k), -0.5 * o.beta);
    spectrum[k] = std::polar(a, phase);
    if (k == n / 2) spectrum[k] = {spectrum[k].real(), 0.0};  // Nyquist bin of a real signal is real
    else spectrum[n - k] = std::conj(spectrum[k]);
  }
  // Level L: the bins below its Nyquist (k <= m/2 for m = n / 2^L entries), the same scale.
  Eigen::FFT<double> fft;
  double scale = 0.0;
  for (std::size_t m = n; m >= 4; m /= 2) {
    std::vector<std::complex<double>> band(m, {0.0, 0.0}), signal;
    for (std::size_t k = 1; k <= m / 2; ++k) {
      band[k] = spectrum[k];
      if (k < m / 2) band[m - k] = spectrum[n - k];
      else band[k] = {spectrum[k].real(), 0.0};  // its own Nyquist bin, real
    }
    fft.inv(signal, band);
    std::vector<double> table(m);
    // Eigen's inverse divides by the size; times m / n keeps every level on level 0's amplitude.
    for (std::size_t i = 0; i < m; ++i) table[i] = signal[i].real() * double(m) / double(n);
    if (m == n) {
      double power = 0.0;
      for (double x : table) power += x * x;
      scale = 1.0 / std::sqrt(power / double(n));
    }
    for (double& x : table) x *= scale;
    levels_.push_back(std::move(table));
  }
}

double RoughnessProfile::at(double distance_m, std::size_t level) const {
  const std::vector<double>& t = levels_[level];
  const double n = double(t.size());
  double x = distance_m / (options_.spacing_m * double(std::size_t(1) << level));
  x -= n * std::floor(x / n);  // into [0, n)
  std::size_t i = std::size_t(x);
  if (i >= t.size()) i = 0;  // x rounded up to n
  const double frac = x - double(i);
  const std::size_t j = (i + 1) & (t.size() - 1);
  return t[i] + frac * (t[j] - t[i]);
}

std::size_t microLevel(const RoughnessProfile& profile, double s0, double s1, std::size_t count) {
  // Entries advanced per sample at level 0; each level halves it.
  double per_sample = std::fabs(s1 - s0) / (profile.options().spacing_m * double(count));
  std::size_t level = 0;
  while (per_sample > 1.0 && level + 1 < profile.levels()) per_sample *= 0.5, ++level;
  return level;
}

double microForceAt(const RoughnessProfile& profile, std::size_t level, double s0, double s1, double f0, double f1,
                    std::size_t n, std::size_t count) {
  const double t = double(n) / double(count);
  const double f = f0 + t * (f1 - f0);
  return f == 0.0 ? 0.0 : profile.options().amplitude * f * profile.at(s0 + t * (s1 - s0), level);
}

void microForce(const RoughnessProfile& profile, double s0, double s1, double f0, double f1, std::span<double> out) {
  const std::size_t level = microLevel(profile, s0, s1, out.size());
  for (std::size_t n = 0; n < out.size(); ++n) out[n] = microForceAt(profile, level, s0, s1, f0, f1, n, out.size());
}

}  // namespace thx::audio
