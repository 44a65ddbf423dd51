#pragma once
// Short-time Fourier transform for looking at and comparing sounds: Hann window, radix-2 FFT,
// magnitude in dB. Used by wav-spectrogram and by the synthesis benchmark's spectral distance.
// Not real-time code (it allocates).
#include <cstddef>
#include <span>
#include <vector>

namespace thx::audio {

struct StftOptions {
  std::size_t window = 2048;  // samples, a power of two >= 2
  std::size_t hop = 512;      // samples between frame starts, >= 1
};

struct Spectrogram {
  double sample_rate_hz = 0;
  std::size_t window = 0, hop = 0;
  std::size_t frames = 0, bins = 0;  // bins = window / 2 + 1 (0 Hz ... Nyquist)
  // frames x bins, frame-major: 20 log10 of the magnitude, scaled so that a sine of amplitude A
  // centred on a bin reads 20 log10(A / 2); floored at -240 dB.
  std::vector<float> db;

  float at(std::size_t frame, std::size_t bin) const { return db[frame * bins + bin]; }
  double binHz(std::size_t bin) const { return double(bin) * sample_rate_hz / double(window); }
  double frameSeconds(std::size_t frame) const { return double(frame * hop) / sample_rate_hz; }
};

// Frame i covers samples [i hop, i hop + window), zero past the end; at least one frame.
// Throws std::logic_error (a caller's mistake: wav-spectrogram checks its options) on a window
// that is not a power of two or a zero hop.
Spectrogram stft(std::span<const float> samples, double sample_rate_hz, const StftOptions& options);

// Log-spectral distance in dB between two spectrograms of the same shape: per frame, the RMS
// over bins of the dB difference, each spectrum floored at `floor_db` below `reference`'s peak
// (so inaudibly quiet bins do not dominate); then the mean over frames.
double logSpectralDistance(const Spectrogram& reference, const Spectrogram& other, double floor_db = 80.0);

}  // namespace thx::audio
