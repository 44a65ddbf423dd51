#include "clients/audio/resonator_bank.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace thx::audio {

ResonatorBank::ResonatorBank(double sample_rate_hz, std::size_t capacity)
    : sample_rate_hz_(sample_rate_hz),
      a1_(capacity, 0.0),
      a2_(capacity, 0.0),
      b_(capacity, 0.0),
      y_(capacity, 0.0),
      y_prev_(capacity, 0.0),
      pending_(capacity, 0.0) {}

bool ResonatorBank::setModes(std::span<const double> frequency_hz, std::span<const double> decay_per_s) {
  if (frequency_hz.size() != decay_per_s.size() || frequency_hz.size() > capacity()) return false;
  const double nyquist = 0.5 * sample_rate_hz_;
  for (std::size_t k = 0; k < frequency_hz.size(); ++k)
    if (!(frequency_hz[k] > 0 && frequency_hz[k] < nyquist && decay_per_s[k] >= 0 && std::isfinite(decay_per_s[k])))
      return false;
  count_ = frequency_hz.size();
  for (std::size_t k = 0; k < count_; ++k) {
    const double wd = 2.0 * std::numbers::pi * frequency_hz[k];
    const double r = std::exp(-decay_per_s[k] / sample_rate_hz_);
    const double theta = wd / sample_rate_hz_;
    a1_[k] = 2.0 * r * std::cos(theta);
    a2_[k] = -r * r;
    b_[k] = r * std::sin(theta) / wd;
  }
  silence();
  return true;
}

void ResonatorBank::silence() {
  std::fill(y_.begin(), y_.end(), 0.0);
  std::fill(y_prev_.begin(), y_prev_.end(), 0.0);
  std::fill(pending_.begin(), pending_.end(), 0.0);
  any_pending_ = false;
}

void ResonatorBank::strike(std::span<const double> modal_impulse) {
  const std::size_t n = std::min(modal_impulse.size(), count_);
  for (std::size_t k = 0; k < n; ++k) pending_[k] += modal_impulse[k];
  any_pending_ = any_pending_ || n > 0;
}

void ResonatorBank::strikeMode(std::size_t mode, double modal_impulse) {
  if (mode >= count_) return;
  pending_[mode] += modal_impulse;
  any_pending_ = true;
}

template <class Sample>
void ResonatorBank::renderImpl(std::span<Sample> out) {
  if (out.empty()) return;
  const std::size_t m = std::min(count_, budget_);
  last_rendered_ = m;
  double* __restrict y = y_.data();
  double* __restrict yp = y_prev_.data();
  const double* __restrict a1 = a1_.data();
  const double* __restrict a2 = a2_.data();
  const double* __restrict b = b_.data();
  std::size_t n = 0;
  if (any_pending_) {
    // The first sample carries the struck impulses into y[n+1].
    double sum = 0.0;
    for (std::size_t k = 0; k < m; ++k) {
      sum += y[k];
      const double next = a1[k] * y[k] + a2[k] * yp[k] + b[k] * pending_[k];
      yp[k] = y[k];
      y[k] = next;
      pending_[k] = 0.0;
    }
    out[0] = Sample(sum);
    // Impulses of modes beyond the budget wait until it admits them.
    any_pending_ = m < count_;
    n = 1;
  }
  for (; n < out.size(); ++n) {
    double sum = 0.0;
    for (std::size_t k = 0; k < m; ++k) {
      sum += y[k];
      const double next = a1[k] * y[k] + a2[k] * yp[k];
      yp[k] = y[k];
      y[k] = next;
    }
    out[n] = Sample(sum);
  }
}

void ResonatorBank::render(std::span<double> out) { renderImpl(out); }
void ResonatorBank::render(std::span<float> out) { renderImpl(out); }

}  // namespace thx::audio
