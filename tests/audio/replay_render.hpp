#pragma once
// audio-client run on a recorded session as a user runs it, for the tests that read its WAV
// (test_mute_replay.cpp, test_pen_mix.cpp): its output kept beside the WAV and printed (the
// context of their [measured] lines), the WAV's samples read back at 44.1 kHz.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "tests/support/process.hpp"
#include "tests/support/rendered_sound.hpp"

namespace thx::audio::test {

// `arguments`: every option but --wav. Empty when audio-client failed (a test failure naming its output).
inline std::vector<float> replayRender(const std::string& arguments, const std::string& wav) {
  EXPECT_EQ(thx::test::shellStatus(std::string(THX_AUDIO_CLIENT) + " " + arguments + " --wav " + wav + " > " + wav + ".out 2>&1"), 0)
      << thx::test::slurp(wav + ".out");
  std::printf("%s", thx::test::slurp(wav + ".out").c_str());
  int rate = 0;
  std::vector<float> x = thx::test::readWavSamples(wav, rate);
  EXPECT_EQ(rate, 44100);
  return x;
}

}  // namespace thx::audio::test
