#pragma once
// Micro-level excitation (docs/audio.md §4a): fractal 1/f^beta roughness read along the distance
// a contact has travelled, not along time, so its pitch follows the tangential speed by
// construction (twice the speed reads the same profile twice as fast) and its loudness follows
// the normal force (force = amplitude x F_n x profile).
//
// The profile is precomputed once: a periodic table of `length` entries `spacing_m` apart whose
// power spectrum falls as k^-beta (amplitude k^(-beta/2), seeded random phases, inverse FFT),
// zero mean, unit RMS. Reading interpolates linearly between entries. Deterministic: the same
// options give the same table on every run.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace thx::audio {

struct RoughnessOptions {
  double beta = 1.0;          // spectral exponent: power ∝ 1/f^beta (pink noise at 1)
  double amplitude = 0.03;    // RMS micro force per newton of normal force (dimensionless)
  double spacing_m = 1e-5;    // distance between table entries (the finest roughness wavelength is 2x this)
  std::size_t length = 1u << 15;  // entries, a power of two; the profile repeats every length x spacing_m
  std::uint64_t seed = 1;
};

class RoughnessProfile {
 public:
  // Throws std::invalid_argument on a length that is not a power of two >= 4, a spacing <= 0 or
  // beta outside [0, 4].
  explicit RoughnessProfile(const RoughnessOptions& options);

  // The profile at a travelled distance (m), periodic, linearly interpolated; unit RMS.
  double at(double distance_m) const;

  std::span<const double> table() const { return table_; }
  const RoughnessOptions& options() const { return options_; }

 private:
  RoughnessOptions options_;
  std::vector<double> table_;
};

// The micro force of one servo segment, sample by sample: distance and normal force go linearly
// from (s0, f0) to (s1, f1) over out.size() samples (the first sample at the segment's start).
// out[n] = amplitude * f(n) * profile(s(n)). Zero normal force gives exact zeros. Allocation-free.
void microForce(const RoughnessProfile& profile, double s0, double s1, double f0, double f1, std::span<double> out);

}  // namespace thx::audio
