#pragma once
// Reading a sound file through libsndfile (WAV, FLAC, AIFF, ...), mixed down to mono.
#include <string>
#include <vector>

namespace thx::audio {

struct MonoSound {
  double sample_rate_hz = 0;
  int channels = 0;  // in the file; samples are their mean
  std::vector<float> samples;
};

// Throws thx::Error (Io) naming the file: missing, unreadable, not a sound file, or empty.
MonoSound readMonoSound(const std::string& path);

}  // namespace thx::audio
