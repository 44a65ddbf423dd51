#pragma once
// A spectrogram as a picture: time to the right, frequency up (linear, labelled in kHz), the
// level in dB as a colour map (inferno) with its scale bar. Drawn with OpenCV imgproc, written
// as PNG by thx::tex::writePng (no OpenCV codecs).
#include <string>

#include "clients/audio/spectrogram/stft.hpp"

namespace thx::audio {

struct SpectrogramImageOptions {
  int width = 1000, height = 420;  // the plot area in pixels; margins are added around it
  double range_db = 90.0;          // colours span [peak - range_db, peak]
  double max_hz = 0;               // top of the frequency axis; 0 = Nyquist
  std::string title;
};

// Throws thx::Error (Io) naming `png_path` if it cannot be written.
void writeSpectrogramPng(const std::string& png_path, const Spectrogram& s, const SpectrogramImageOptions& options);

}  // namespace thx::audio
