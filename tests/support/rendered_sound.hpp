#pragma once
// For the audio tests that render a recorded session to a WAV and look for the texture's joints in
// it (tests/audio/test_*_onsets.cpp): the WAV's samples, and which texels of a scene's texture are
// mortar; a fixture with a fresh folder and the shell. Links libsndfile and thx_scenes.
#include <gtest/gtest.h>
#include <sndfile.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "scenes/scene_loader.hpp"
#include "scenes/surface_texture.hpp"
#include "tests/support/onset_detector.hpp"
#include "tests/support/process.hpp"
#include "tests/support/temp_dir.hpp"

namespace thx::test {

// Every sample of a sound file, channels interleaved; empty (and rate 0) if it cannot be read.
inline std::vector<float> readWavSamples(const std::string& path, int& rate) {
  SF_INFO info{};
  rate = 0;
  SNDFILE* f = sf_open(path.c_str(), SFM_READ, &info);
  if (!f) return {};
  std::vector<float> x(std::size_t(info.frames) * std::size_t(info.channels));
  sf_readf_float(f, x.data(), info.frames);
  sf_close(f);
  rate = info.samplerate;
  return x;
}

// The scene's texture built as a relief map (whatever its representation): a texel is mortar when
// its relief lies deeper than halfway between the highest face and the deepest floor.
class MortarMap {
 public:
  explicit MortarMap(const std::string& scene_file) : relief_(build(scene_file)) {
    float lo = 1e9f, hi = -1e9f;
    for (int j = 0; j < relief_.height(); ++j)
      for (int i = 0; i < relief_.width(); ++i) lo = std::min(lo, relief_.depth(i, j)), hi = std::max(hi, relief_.depth(i, j));
    half_ = 0.5f * (lo + hi);
  }
  // Texel indices wrap.
  bool isMortar(int i, int j) const {
    const int w = relief_.width(), h = relief_.height();
    return relief_.depth(((i % w) + w) % w, ((j % h) + h) % h) > half_;
  }

 private:
  static tex::TextureMap build(const std::string& scene_file) {
    scene::Scene s = scene::loadScene(scene_file);
    s.surface.representation = tex::Representation::Relief;
    return scene::buildSurfaceTexture(s);
  }
  tex::TextureMap relief_;
  float half_ = 0.0f;
};

// The onsets of a WAV (onset_detector.hpp, its other options the defaults; empty if the file
// cannot be read).
inline std::vector<double> wavOnsets(const std::string& wav, double min_gap_s) {
  int rate = 0;
  const std::vector<float> x = readWavSamples(wav, rate);
  if (rate <= 0) return {};
  OnsetOptions detect;
  detect.min_gap_s = min_gap_s;
  return detectOnsets(x, rate, detect);
}

// One "[measured]" line: crossings and onsets, each as a count and a rate over `span_s`.
inline void printRates(const std::vector<double>& crossings, const std::vector<double>& onsets, double span_s) {
  std::printf("[measured] %zu mortar crossings (%.2f /s), %zu onsets (%.2f /s) over %.2f s\n", crossings.size(),
              double(crossings.size()) / span_s, onsets.size(), double(onsets.size()) / span_s, span_s);
}

// Each onset against its nearest crossing (s): how many lie within (before_s, after_s) of it (a
// line for each that does not), and the earliest and latest offsets (a "[measured]" line).
inline std::size_t onsetsAtCrossings(const std::vector<double>& onsets, const std::vector<double>& crossings,
                                     double before_s, double after_s) {
  std::size_t matched = 0;
  double earliest = 1e9, latest = -1e9;
  for (double t : onsets) {
    double nearest = 1e9;
    for (double c : crossings)
      if (std::fabs(t - c) < std::fabs(nearest)) nearest = t - c;
    earliest = std::min(earliest, nearest), latest = std::max(latest, nearest);
    if (nearest > -before_s && nearest < after_s) ++matched;
    else std::printf("onset at %.4f s: %+.4f s from the nearest crossing\n", t, nearest);
  }
  std::printf("[measured] onsets %+.1f to %+.1f ms from their crossings\n", earliest * 1e3, latest * 1e3);
  return matched;
}

// A test that runs the programs as a user does, in a folder of its own (removed afterwards).
class SessionTest : public ::testing::Test {
 protected:
  std::string path(const std::string& name) const { return dir_.file(name); }
  static std::string fileBytes(const std::string& file) { return slurp(file); }
  static int run(const std::string& command) { return shellStatus(command); }
#ifdef THX_HAPTICD
  // hapticd records `scene` in lock-step to session.lcm (its output in hapticd.out).
  int recordSession(const std::string& scene, const std::string& options = "") const {
    return run(std::string(THX_HAPTICD) + " --scene " + scene + " --lockstep --no-lcm --no-mlock " + options + " --record " +
               path("session.lcm") + " --quiet > " + path("hapticd.out"));
  }
#endif
  TempDir dir_{"thx_session"};
};

}  // namespace thx::test
