#pragma once
// The sound cue as a simulated participant hears it: the audio client's own synthesis
// (clients/audio/synthesis/surface_sound.hpp: the surface slab's modal analysis of the scene's material,
// its audible modes, the resonator bank) struck once, 2 s of it rendered, and two things read off
// the samples (docs/study.md §6.1):
//  - pitch: log10 of the RMS frequency of the sound (its spectrum's second moment, from the
//    samples' differences: Parseval), what sets how high it sounds;
//  - ring: log10 of the early decay time, 6 x the time the backward-integrated energy takes to
//    fall 10 dB (a T60 read from its first 10 dB), how long it rings.
// The slab is coarse (kPerceptSlab: 4 x 4 x 1 Tet10 cells, 12 modes, no cache) so a trial's
// percept costs milliseconds: its modes are not the client's 20 x 20 x 2 slab's, but pitch and
// ring follow the material as they do (the same solver, damping and synthesis).
// A muted scene (audio.mute, Study 1's NAME.nosound) sounds nothing: no features.
#include <optional>
#include <span>
#include <string>

namespace thx::study {

struct SoundPercept {
  double pitch_log10_hz = 0.0;
  double ring_log10_s = 0.0;
};

inline constexpr int kPerceptSlabCells = 4, kPerceptSlabLayers = 1, kPerceptModes = 12;
inline constexpr double kPerceptRenderS = 2.0;

// Throws thx::Error naming the scene file.
std::optional<SoundPercept> hearSurface(const std::string& scene_path);

// The two features of any samples at sample_rate_hz (nothing for silence). For one mode,
// e^{-d t} sin(2 pi f t): pitch log10 f and ring log10 (3 ln 10 / d), its T60, up to the
// render's length.
std::optional<SoundPercept> soundFeatures(std::span<const double> x, double sample_rate_hz);

}  // namespace thx::study
