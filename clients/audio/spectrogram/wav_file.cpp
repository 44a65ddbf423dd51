#include "clients/audio/spectrogram/wav_file.hpp"

#include <sndfile.h>

#include "base/error.hpp"

namespace thx::audio {

MonoSound readMonoSound(const std::string& path) {
  SF_INFO info{};
  SNDFILE* f = sf_open(path.c_str(), SFM_READ, &info);
  if (!f) throw Error(Error::Kind::Io, path + ": cannot be read as a sound file: " + sf_strerror(nullptr));
  MonoSound s;
  s.sample_rate_hz = info.samplerate;
  s.channels = info.channels;
  if (info.frames <= 0 || info.channels <= 0) {
    sf_close(f);
    throw Error(Error::Kind::Io, path + ": holds no samples");
  }
  std::vector<float> interleaved(std::size_t(info.frames) * std::size_t(info.channels));
  const sf_count_t got = sf_readf_float(f, interleaved.data(), info.frames);
  sf_close(f);
  if (got <= 0) throw Error(Error::Kind::Io, path + ": no samples could be read");
  s.samples.resize(std::size_t(got));
  for (std::size_t n = 0; n < s.samples.size(); ++n) {
    float sum = 0;
    for (int c = 0; c < info.channels; ++c) sum += interleaved[n * std::size_t(info.channels) + std::size_t(c)];
    s.samples[n] = sum / float(info.channels);
  }
  return s;
}

}  // namespace thx::audio
