// The STFT behind wav-spectrogram and the benchmark's spectral distance, the sound-file reader
// and the picture: a pure tone lands in its bin at its level; bad files are named.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <functional>
#include <numbers>
#include <string>
#include <vector>

#include "base/error.hpp"
#include "clients/audio/spectrogram/spectrogram_image.hpp"
#include "clients/audio/spectrogram/stft.hpp"
#include "clients/audio/spectrogram/wav_file.hpp"
#include "tests/audio/wav_fixture.hpp"
#include "textures/png_io.hpp"

namespace thx::audio::test_spectrogram {
namespace {

constexpr double kRate = 44100.0;
using test::tone;
using test::writePcm16;

std::size_t loudestBin(const Spectrogram& s, std::size_t frame) {
  std::size_t best = 0;
  for (std::size_t k = 1; k < s.bins; ++k)
    if (s.at(frame, k) > s.at(frame, best)) best = k;
  return best;
}

TEST(Stft, AToneCentredOnABinPeaksThereAtHalfItsAmplitude) {
  const double f = 46 * kRate / 2048;  // bin 46 exactly (990.5 Hz)
  const Spectrogram s = stft(tone(f, 0.5, 8192), kRate, {2048, 512});
  EXPECT_EQ(s.bins, 1025u);
  EXPECT_EQ(s.frames, 13u);  // 1 + ceil((8192 - 2048) / 512)
  for (std::size_t frame = 0; frame + 4 < s.frames; ++frame) {  // frames wholly inside the tone
    EXPECT_EQ(loudestBin(s, frame), 46u) << frame;
    EXPECT_NEAR(s.at(frame, 46), 20 * std::log10(0.25), 0.01) << frame;
  }
  EXPECT_NEAR(s.binHz(46), f, 1e-9);
}

TEST(Stft, AToneBetweenBinsPeaksInTheNearestBin) {
  for (double f : {440.0, 1234.5, 15000.0}) {
    const Spectrogram s = stft(tone(f, 1.0, 4096), kRate, {1024, 256});
    const std::size_t expected = std::size_t(std::lround(f * 1024 / kRate));
    EXPECT_EQ(loudestBin(s, 2), expected) << f;
    // A Hann window loses at most 1.42 dB between bins (its scalloping loss).
    EXPECT_GT(s.at(2, expected), 20 * std::log10(0.5) - 1.43) << f;
  }
}

TEST(Stft, SilenceIsTheFloorAndBadSettingsAreRefused) {
  const Spectrogram s = stft(std::vector<float>(100, 0.0f), kRate, {256, 64});
  EXPECT_EQ(s.frames, 1u);
  EXPECT_EQ(*std::max_element(s.db.begin(), s.db.end()), -240.0f);
  EXPECT_THROW(stft(std::vector<float>(100), kRate, {1000, 64}), std::logic_error);
  EXPECT_THROW(stft(std::vector<float>(100), kRate, {1024, 0}), std::logic_error);
}

TEST(Stft, LogSpectralDistanceIsZeroForTheSameSoundAndGrowsWithADetunedOne) {
  const StftOptions o{2048, 512};
  const Spectrogram a = stft(tone(1000, 0.5, 16384), kRate, o);
  EXPECT_EQ(logSpectralDistance(a, a), 0.0);
  const double near = logSpectralDistance(a, stft(tone(1001, 0.5, 16384), kRate, o));
  const double far = logSpectralDistance(a, stft(tone(1100, 0.5, 16384), kRate, o));
  EXPECT_GT(near, 0.0);
  EXPECT_GT(far, 2 * near);
}

TEST(WavSpectrogram, ReadsAToneAndDrawsItsPicture) {
  const std::string wav = ::testing::TempDir() + "thx_tone.wav", png = ::testing::TempDir() + "thx_tone.png";
  writePcm16(wav, tone(3000, 0.5, 22050), 44100);
  const MonoSound sound = readMonoSound(wav);
  EXPECT_EQ(sound.sample_rate_hz, 44100.0);
  EXPECT_EQ(sound.channels, 1);
  ASSERT_EQ(sound.samples.size(), 22050u);
  const Spectrogram s = stft(sound.samples, sound.sample_rate_hz, {2048, 256});
  EXPECT_EQ(loudestBin(s, 10), std::size_t(std::lround(3000 * 2048 / 44100.0)));
  SpectrogramImageOptions o;
  o.width = 300, o.height = 200, o.title = "tone";
  writeSpectrogramPng(png, s, o);
  const tex::RawImage image = tex::readPng(png);
  EXPECT_GT(image.width, 300);  // the plot area and its margins
  EXPECT_GT(image.height, 200);
  EXPECT_EQ(image.channels, 3);
}

std::string messageOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const thx::Error& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(WavSpectrogram, ErrorsNameTheFile) {
  const std::string missing = ::testing::TempDir() + "thx_no_such_sound.wav";
  EXPECT_NE(messageOf([&] { readMonoSound(missing); }).find(missing), std::string::npos);
  const std::string text = ::testing::TempDir() + "thx_not_a_sound.wav";
  std::ofstream(text) << "this is not a sound file\n";
  const std::string m = messageOf([&] { readMonoSound(text); });
  EXPECT_NE(m.find(text), std::string::npos) << m;
  const std::string unwritable = ::testing::TempDir() + "thx_no_such_dir/out.png";
  const Spectrogram s = stft(tone(440, 0.5, 4096), kRate, {1024, 256});
  const std::string w = messageOf([&] { writeSpectrogramPng(unwritable, s, {}); });
  EXPECT_NE(w.find(unwritable), std::string::npos) << w;
}

}  // namespace
}  // namespace thx::audio::test_spectrogram
