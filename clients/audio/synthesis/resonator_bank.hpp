#pragma once
// A bank of damped modal resonators, the exact impulse-invariant two-pole recurrence per mode
// (docs/audio.md §3): with R = exp(-d/fs), theta = omega_d/fs,
//   y[n+1] = 2R cos(theta) y[n] - R^2 y[n-1] + (R sin(theta) / omega_d) g[n]
// equals the closed form (g/omega_d) e^{-d t} sin(omega_d t) of a modal impulse g (N s per unit
// modal mass, i.e. u_i . J with M-orthonormal shapes) at the sample times, so it has no
// frequency warping and no decay error at any frequency below Nyquist.
//
// Structure of arrays (coefficients and states in separate contiguous arrays), vectorised across
// modes by resonator_kernel.hpp (-O3, the instruction set chosen at run time). Real-time safe
// after construction: setModes (up to the capacity), strike and render never allocate or lock.
// ResonatorBank computes in double, ResonatorBankFloat in float (more modes per core, in the
// difference form that keeps low modes in tune; its error against double: docs/audio.md §3).
#include <cstddef>
#include <span>
#include <vector>

#include "clients/audio/synthesis/resonator_kernel.hpp"

namespace thx::audio {

template <class Real>
class BasicResonatorBank {
 public:
  // Allocates room for `capacity` modes. sample_rate_hz > 0. Uses the fastest instruction set
  // this CPU supports (bestIsa()).
  BasicResonatorBank(double sample_rate_hz, std::size_t capacity);

  // Replaces the modes (damped frequency in Hz, decay d in 1/s, so the envelope is e^{-d t}) and
  // silences them. Returns false (and changes nothing) if there are more than the capacity, the
  // spans differ in length, or a frequency is not in (0, Nyquist) or a decay is negative.
  // Coefficients are computed in double and then rounded to Real.
  bool setModes(std::span<const double> frequency_hz, std::span<const double> decay_per_s);

  // Adds a modal impulse to every mode (modal_impulse.size() must equal size(); extra values are
  // ignored, missing ones count as 0). It acts at the first sample the next render() produces.
  void strike(std::span<const double> modal_impulse);
  void strikeMode(std::size_t mode, double modal_impulse);

  // Writes the next out.size() samples of the sum of the modal displacements q_i (a contact
  // microphone's view, docs/audio.md §3).
  void render(std::span<double> out);
  void render(std::span<float> out);

  // Quality scaling under load: render() computes at most `modes` modes per block, the first
  // ones (setModes' order is the priority order); the others are silent and keep their state
  // until the budget admits them again. Default: no limit.
  void setBudget(std::size_t modes) { budget_ = modes; }
  std::size_t budget() const { return budget_; }
  // Modes computed by the last render() (<= the budget).
  std::size_t lastRenderedModes() const { return last_rendered_; }

  // The kernel's instruction set; setIsa returns false (and keeps the current one) if this CPU
  // does not support it. Every choice gives the same samples (resonator_kernel.hpp).
  Isa isa() const { return isa_; }
  bool setIsa(Isa isa);

  void silence();
  std::size_t size() const { return count_; }
  std::size_t capacity() const { return capacity_; }
  double sampleRate() const { return sample_rate_hz_; }

 private:
  template <class Sample>
  void renderImpl(std::span<Sample> out);
  ResonatorArrays<Real> arrays(bool with_pending);

  double sample_rate_hz_;
  std::size_t capacity_;
  std::size_t count_ = 0;
  // Per mode, padded to whole vectors of lanes: c1, c2, b and the states y[n] (the next sample
  // out) and x (y[n-1], or y[n] - y[n-1] in float: resonator_kernel.hpp).
  std::vector<Real> a1_, a2_, b_;
  std::vector<Real> y_, y_prev_;
  std::vector<Real> pending_;     // impulses struck since the last render
  std::vector<Real> lanes_, block_;  // the kernel's scratch
  bool any_pending_ = false;
  std::size_t budget_ = static_cast<std::size_t>(-1);
  std::size_t last_rendered_ = 0;
  Isa isa_;
  ResonatorKernel<Real> kernel_;
};

extern template class BasicResonatorBank<double>;
extern template class BasicResonatorBank<float>;

// A class, not an alias, so that `class ResonatorBank;` still declares it.
class ResonatorBank : public BasicResonatorBank<double> {
 public:
  using BasicResonatorBank<double>::BasicResonatorBank;
};

class ResonatorBankFloat : public BasicResonatorBank<float> {
 public:
  using BasicResonatorBank<float>::BasicResonatorBank;
};

}  // namespace thx::audio
