#include "clients/audio/synthesis/resonator_bank.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace thx::audio {
namespace {

template <class Real>
std::size_t padded(std::size_t modes) {
  constexpr std::size_t w = kResonatorLanes<Real>;
  return (modes + w - 1) / w * w;
}

}  // namespace

template <class Real>
BasicResonatorBank<Real>::BasicResonatorBank(double sample_rate_hz, std::size_t capacity)
    : sample_rate_hz_(sample_rate_hz),
      capacity_(capacity),
      a1_(padded<Real>(capacity), Real(0)),
      a2_(padded<Real>(capacity), Real(0)),
      b_(padded<Real>(capacity), Real(0)),
      y_(padded<Real>(capacity), Real(0)),
      y_prev_(padded<Real>(capacity), Real(0)),
      pending_(padded<Real>(capacity), Real(0)),
      lanes_(kResonatorBlock * kResonatorLanes<Real>, Real(0)),
      block_(kResonatorBlock, Real(0)),
      isa_(bestIsa()),
      kernel_(resonatorKernel<Real>(isa_)) {}

template <class Real>
bool BasicResonatorBank<Real>::setIsa(Isa isa) {
  if (!isaSupported(isa)) return false;
  isa_ = isa;
  kernel_ = resonatorKernel<Real>(isa);
  return true;
}

template <class Real>
bool BasicResonatorBank<Real>::setModes(std::span<const double> frequency_hz, std::span<const double> decay_per_s) {
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
    if constexpr (kResonatorDifferenceForm<Real>) {
      const double s = std::sin(0.5 * theta);
      const double one_minus_r = -std::expm1(-decay_per_s[k] / sample_rate_hz_);
      // 2R cos(theta) - 1 - R^2 written without cancellation.
      a1_[k] = Real(-one_minus_r * one_minus_r - 4.0 * r * s * s);
      a2_[k] = Real(r * r);
    } else {
      a1_[k] = Real(2.0 * r * std::cos(theta));
      a2_[k] = Real(-r * r);
    }
    b_[k] = Real(r * std::sin(theta) / wd);
  }
  // Padding lanes stay all-zero, so they add exactly 0 to every sample.
  std::fill(a1_.begin() + std::ptrdiff_t(count_), a1_.end(), Real(0));
  std::fill(a2_.begin() + std::ptrdiff_t(count_), a2_.end(), Real(0));
  std::fill(b_.begin() + std::ptrdiff_t(count_), b_.end(), Real(0));
  silence();
  return true;
}

template <class Real>
void BasicResonatorBank<Real>::silence() {
  std::fill(y_.begin(), y_.end(), Real(0));
  std::fill(y_prev_.begin(), y_prev_.end(), Real(0));
  std::fill(pending_.begin(), pending_.end(), Real(0));
  any_pending_ = false;
}

template <class Real>
void BasicResonatorBank<Real>::strike(std::span<const double> modal_impulse) {
  const std::size_t n = std::min(modal_impulse.size(), count_);
  for (std::size_t k = 0; k < n; ++k) pending_[k] += Real(modal_impulse[k]);
  any_pending_ = any_pending_ || n > 0;
}

template <class Real>
void BasicResonatorBank<Real>::strikeMode(std::size_t mode, double modal_impulse) {
  if (mode >= count_) return;
  pending_[mode] += Real(modal_impulse);
  any_pending_ = true;
}

template <class Real>
ResonatorArrays<Real> BasicResonatorBank<Real>::arrays(bool with_pending) {
  return {a1_.data(), a2_.data(), b_.data(), y_.data(), y_prev_.data(), with_pending ? pending_.data() : nullptr};
}

template <class Real>
template <class Sample>
void BasicResonatorBank<Real>::renderImpl(std::span<Sample> out) {
  if (out.empty()) return;
  const std::size_t m = std::min(count_, budget_);
  last_rendered_ = m;
  for (std::size_t done = 0; done < out.size();) {
    const std::size_t n = std::min(kResonatorBlock, out.size() - done);
    kernel_(arrays(any_pending_), m, n, lanes_.data(), block_.data());
    // Impulses of modes beyond the budget wait until it admits them.
    any_pending_ = any_pending_ && m < count_;
    for (std::size_t i = 0; i < n; ++i) out[done + i] = Sample(block_[i]);
    done += n;
  }
}

template <class Real>
void BasicResonatorBank<Real>::render(std::span<double> out) {
  renderImpl(out);
}
template <class Real>
void BasicResonatorBank<Real>::render(std::span<float> out) {
  renderImpl(out);
}

template class BasicResonatorBank<double>;
template class BasicResonatorBank<float>;

}  // namespace thx::audio
