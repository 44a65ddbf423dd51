#include "clients/audio/fractal_roughness.hpp"

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
    throw std::invalid_argument("roughness length: expected a power of two >= 4, got " + std::to_string(n));
  if (!(o.spacing_m > 0.0))
    throw std::invalid_argument("roughness spacing: expected > 0 m, got " + std::to_string(o.spacing_m));
  if (!(o.beta >= 0.0 && o.beta <= 4.0))
    throw std::invalid_argument("roughness beta: expected a number in [0, 4], got " + std::to_string(o.beta));

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
  Eigen::FFT<double> fft;
  std::vector<std::complex<double>> signal;
  fft.inv(signal, spectrum);
  table_.resize(n);
  double power = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    table_[i] = signal[i].real();
    power += table_[i] * table_[i];
  }
  const double scale = 1.0 / std::sqrt(power / double(n));
  for (double& x : table_) x *= scale;
}

double RoughnessProfile::at(double distance_m) const {
  const double n = double(table_.size());
  double x = distance_m / options_.spacing_m;
  x -= n * std::floor(x / n);  // into [0, n)
  std::size_t i = std::size_t(x);
  if (i >= table_.size()) i = 0;  // x rounded up to n
  const double frac = x - double(i);
  const std::size_t j = (i + 1) & (table_.size() - 1);
  return table_[i] + frac * (table_[j] - table_[i]);
}

void microForce(const RoughnessProfile& profile, double s0, double s1, double f0, double f1, std::span<double> out) {
  const double count = double(out.size());
  const double a = profile.options().amplitude;
  for (std::size_t n = 0; n < out.size(); ++n) {
    const double t = double(n) / count;
    const double f = f0 + t * (f1 - f0);
    out[n] = f == 0.0 ? 0.0 : a * f * profile.at(s0 + t * (s1 - s0));
  }
}

}  // namespace thx::audio
