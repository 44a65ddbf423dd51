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
//
// Anti-aliasing: a fast contact would read more than one entry per audio sample and fold the
// finest roughness back into the audible band. So the profile is also kept band-limited at every
// octave: level L is the same profile with only the spectral bins k <= length / 2^(L+1), sampled
// every spacing x 2^L (the lower half of the spectrum, inverse-transformed at half the size), and
// microForce reads the finest level that advances at most one entry per sample.
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
  // Throws std::logic_error (a caller's mistake: the scene loader checks a scene's roughness) on
  // a length that is not a power of two >= 4, a spacing <= 0 or beta outside [0, 4].
  explicit RoughnessProfile(const RoughnessOptions& options);

  // The profile at a travelled distance (m), periodic, linearly interpolated; unit RMS at level 0.
  // Level L (< levels()) is band-limited to wavelengths >= 2 x spacing x 2^L.
  double at(double distance_m, std::size_t level = 0) const;

  std::span<const double> table(std::size_t level = 0) const { return levels_[level]; }
  std::size_t levels() const { return levels_.size(); }
  const RoughnessOptions& options() const { return options_; }

 private:
  RoughnessOptions options_;
  std::vector<std::vector<double>> levels_;  // level L: length / 2^L entries, down to 4
};

// The micro force of one servo segment, sample by sample: distance and normal force go linearly
// from (s0, f0) to (s1, f1) over out.size() samples (the first sample at the segment's start).
// out[n] = amplitude * f(n) * profile(s(n)), read at the finest level that advances at most one
// entry per sample (level 0 for |s1 - s0| <= out.size() x spacing). Zero normal force gives exact
// zeros. Allocation-free.
void microForce(const RoughnessProfile& profile, double s0, double s1, double f0, double f1, std::span<double> out);

// microForce one sample at a time (the live callback renders a segment across its blocks):
// the level it reads for a segment of `count` samples, and its sample n (< count).
std::size_t microLevel(const RoughnessProfile& profile, double s0, double s1, std::size_t count);
double microForceAt(const RoughnessProfile& profile, std::size_t level, double s0, double s1, double f0, double f1,
                    std::size_t n, std::size_t count);

}  // namespace thx::audio
