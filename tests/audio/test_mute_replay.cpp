// A muted scene (audio: {mute: true}, docs/scenes.md) in an offline render, as Study 1's "no
// sound" trial uses it (NAME.nosound, docs/study.md §7): hapticd records a pen stroke across
// grooves in lock-step; hellos switching to the scene's muted twin and back are written into a
// copy of the log, as hapticd --record writes them at a switch; audio-client renders both logs.
// The muted stretch is exact zeros, sound is there before it and comes back after the switch
// back, and the same stretch of the unmuted render is not silent.
#include <gtest/gtest.h>
#include <lcm/lcm-cpp.hpp>

#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include <thx_msgs/contact_t.hpp>
#include <thx_msgs/hello_t.hpp>
#include <thx_msgs/protocol.hpp>

#include "tests/audio/replay_render.hpp"
#include "tests/support/rendered_sound.hpp"
#include "thx_msgs/log_reader.hpp"

namespace test_mute_replay {

namespace {

// 128² grooves (ceramic), one stroke across them at 0.1 m/s: 1.2 s in contact after a 0.3 s hold.
const std::string kScene = R"(version: 1
name: grooves stroked
surface:
  size: [0.2, 0.2]
  texture: {generator: grooves, size: 128, params: {extent: 0.2, period: 0.02, depth: 0.001}}
  representation: relief
  material: ceramic
device:
  type: sim
  model: phantom_desktop
  stiffness_fraction: 0.6
  damping: 1.0
  script:
    - hold: {duration: 0.3}
    - stroke: {from: [-0.06, 0.01], to: [0.06, 0.01], speed: 0.1, force: 1.0}
    - hold: {duration: 0.1}
)";

class MuteReplay : public thx::test::SessionTest {
 protected:
  // Every event of `in`, with `hellos` (utime, scene) inserted before the first event whose
  // THX_CONTACT utime reaches theirs; the hellos copy the log's first (its fingerprint).
  void withHellos(const std::string& in, const std::string& out, std::vector<std::pair<std::int64_t, std::string>> hellos) {
    lcm::LogFile src(in, "r"), dst(out, "w");
    ASSERT_TRUE(src.good() && dst.good());
    thx_msgs::hello_t first{};
    bool have_first = false;
    std::size_t next = 0;
    std::vector<std::uint8_t> buf;
    while (const lcm::LogEvent* e = src.readNextEvent()) {
      std::string channel = e->channel;
      if (channel == thx_msgs::kChannelHello && !have_first) have_first = first.decode(e->data, 0, e->datalen) > 0;
      if (channel == "THX_CONTACT" && next < hellos.size()) {
        thx_msgs::contact_t c{};
        ASSERT_GT(c.decode(e->data, 0, e->datalen), 0);
        if (c.utime >= hellos[next].first) {
          ASSERT_TRUE(have_first);
          thx_msgs::hello_t h = first;
          h.utime = hellos[next].first;
          h.scene_name = hellos[next].second;
          buf.resize(std::size_t(h.getEncodedSize()));
          h.encode(buf.data(), 0, int(buf.size()));
          lcm::LogEvent he = *e;
          he.channel = thx_msgs::kChannelHello;
          he.datalen = std::int32_t(buf.size());
          he.data = buf.data();
          ASSERT_EQ(dst.writeEvent(&he), 0);
          ++next;
        }
      }
      lcm::LogEvent copy = *e;
      ASSERT_EQ(dst.writeEvent(&copy), 0);
    }
    ASSERT_EQ(next, hellos.size());
  }
  std::vector<float> render(const std::string& log, const std::string& wav) {
    return thx::audio::test::replayRender("--scene " + path("grooves.yaml") + " --replay-log " + log +
                                              " --slab-cells 4 --modes 12 --no-pen --cache-dir " + path("cache"),
                                          wav);
  }
};

double peakIn(const std::vector<float>& x, double from_s, double to_s) {
  double peak = 0.0;
  for (std::size_t n = std::size_t(from_s * 44100); n < std::min(x.size(), std::size_t(to_s * 44100)); ++n)
    peak = std::max(peak, double(std::fabs(x[n])));
  return peak;
}

TEST_F(MuteReplay, AMutedSceneIsExactSilenceAndTheSoundComesBackAfterIt) {
  std::ofstream(path("grooves.yaml")) << kScene;
  std::ofstream(path("grooves_muted.yaml")) << kScene << "audio: {mute: true}\n";
  ASSERT_EQ(recordSession(path("grooves.yaml")), 0) << fileBytes(path("hapticd.out"));
  std::int64_t origin = -1;
  thx_msgs::forEachLogMessage<thx_msgs::contact_t>(path("session.lcm"), "THX_CONTACT", [&](const auto& c, const auto&) {
    if (origin < 0) origin = c.utime;
  });
  ASSERT_GE(origin, 0);
  // Muted from 0.6 s to 1.0 s of the stroke (sample 0 = the first THX_CONTACT).
  withHellos(path("session.lcm"), path("muted.lcm"), {{origin + 600'000, "grooves_muted"}, {origin + 1'000'000, "grooves"}});

  const std::vector<float> plain = render(path("session.lcm"), path("plain.wav"));
  const std::vector<float> muted = render(path("muted.lcm"), path("muted.wav"));
  ASSERT_GT(muted.size(), std::size_t(1.5 * 44100));
  EXPECT_TRUE(fileBytes(path("muted.wav.out")).find("muted scenes (audio.mute): grooves_muted") != std::string::npos);
  // The stroke sounds in the muted stretch when nothing mutes it ...
  EXPECT_GT(peakIn(plain, 0.6, 1.0), 1e-3);
  // ... and is exact zeros (sample 26 460 = 0.6 s through 44 100 = 1.0 s) with the muted twin.
  for (std::size_t n = 26460; n < 44100; ++n) ASSERT_EQ(muted[n], 0.0f) << "sample " << n;
  EXPECT_NE(muted[26459], 0.0f);  // the sample before the switch still rings
  EXPECT_GT(peakIn(muted, 0.3, 0.6), 1e-3);   // sound before the switch,
  EXPECT_GT(peakIn(muted, 1.0, 1.5), 1e-3);   // and again after the switch back
}

}  // namespace

}  // namespace test_mute_replay
