#include "clients/audio/spectrogram/stft.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <stdexcept>
#include <string>

namespace thx::audio {
namespace {

// In-place iterative radix-2 FFT (n a power of two).
void fft(std::vector<std::complex<double>>& x) {
  const std::size_t n = x.size();
  for (std::size_t i = 1, j = 0; i < n; ++i) {
    std::size_t bit = n >> 1;
    for (; j & bit; bit >>= 1) j ^= bit;
    j ^= bit;
    if (i < j) std::swap(x[i], x[j]);
  }
  for (std::size_t len = 2; len <= n; len <<= 1) {
    const double angle = -2.0 * std::numbers::pi / double(len);
    for (std::size_t i = 0; i < n; i += len)
      for (std::size_t k = 0; k < len / 2; ++k) {
        // The twiddle computed directly each time (not by repeated multiplication): exact enough
        // for long windows at the cost of speed this tool does not need.
        const std::complex<double> w = std::polar(1.0, angle * double(k));
        const std::complex<double> u = x[i + k], v = x[i + k + len / 2] * w;
        x[i + k] = u + v;
        x[i + k + len / 2] = u - v;
      }
  }
}

}  // namespace

Spectrogram stft(std::span<const float> samples, double sample_rate_hz, const StftOptions& o) {
  if (o.window < 2 || (o.window & (o.window - 1)) != 0)
    throw std::logic_error("STFT window " + std::to_string(o.window) + ": expected a power of two >= 2");
  if (o.hop == 0) throw std::logic_error("STFT hop 0: expected >= 1");
  Spectrogram s;
  s.sample_rate_hz = sample_rate_hz;
  s.window = o.window;
  s.hop = o.hop;
  s.bins = o.window / 2 + 1;
  s.frames = samples.size() <= o.window ? 1 : 1 + (samples.size() - o.window + o.hop - 1) / o.hop;
  s.db.assign(s.frames * s.bins, -240.0f);
  std::vector<double> hann(o.window);
  double window_sum = 0;
  for (std::size_t i = 0; i < o.window; ++i) {
    hann[i] = 0.5 - 0.5 * std::cos(2.0 * std::numbers::pi * double(i) / double(o.window));  // periodic
    window_sum += hann[i];
  }
  std::vector<std::complex<double>> x(o.window);
  for (std::size_t f = 0; f < s.frames; ++f) {
    const std::size_t start = f * o.hop;
    for (std::size_t i = 0; i < o.window; ++i)
      x[i] = start + i < samples.size() ? hann[i] * double(samples[start + i]) : 0.0;
    fft(x);
    for (std::size_t k = 0; k < s.bins; ++k) {
      const double magnitude = std::abs(x[k]) / window_sum;
      s.db[f * s.bins + k] = float(std::max(-240.0, 20.0 * std::log10(std::max(magnitude, 1e-12))));
    }
  }
  return s;
}

double logSpectralDistance(const Spectrogram& a, const Spectrogram& b, double floor_db) {
  if (a.frames != b.frames || a.bins != b.bins) throw std::logic_error("spectrograms of different shapes");
  const float peak = *std::max_element(a.db.begin(), a.db.end());
  const double floor_at = double(peak) - floor_db;
  double total = 0;
  for (std::size_t f = 0; f < a.frames; ++f) {
    double sum = 0;
    for (std::size_t k = 0; k < a.bins; ++k) {
      const double d = std::max(double(a.at(f, k)), floor_at) - std::max(double(b.at(f, k)), floor_at);
      sum += d * d;
    }
    total += std::sqrt(sum / double(a.bins));
  }
  return total / double(a.frames);
}

}  // namespace thx::audio
