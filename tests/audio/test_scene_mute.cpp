// A muted scene (audio: {mute: true}, docs/scenes.md) in the audio client, in-process: the spans
// of an offline render it silences (scene_mute.hpp), and the live client's scene as
// buildLiveScene makes it: no sources and a muted SynthScene, which LiveSynth plays as exact
// zeros, cutting what rang before; a switch back to the unmuted scene sounds again.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>

#include "clients/audio/live/excitation_feed.hpp"
#include "clients/audio/live/live_scene.hpp"
#include "clients/audio/live/live_synth.hpp"
#include "clients/audio/offline/scene_mute.hpp"
#include "tests/audio/live_fixtures.hpp"
#include "tests/support/temp_dir.hpp"

namespace thx::audio::test_scene_mute {
namespace {

constexpr std::int64_t kMin = std::numeric_limits<std::int64_t>::min(), kMax = std::numeric_limits<std::int64_t>::max();

TEST(SceneMute, SpansFollowTheScenesAsTheScrapeSplitsThem) {
  const auto muted = [](const std::string& name) { return name.ends_with(".nosound"); };
  const std::vector<SceneStart> hellos{{100, "a"},           {200, "a.nosound"}, {250, ""}, {300, "a.nosound"},
                                       {400, "b.nosound"},   {500, "b"},         {600, "c.nosound"}};
  const std::vector<MutedSpan> spans = mutedSpans(hellos, "a", muted);
  ASSERT_EQ(spans.size(), 2u);
  // An empty name or the current scene's is no switch; two muted scenes in a row are one span.
  EXPECT_EQ(spans[0].from_utime, 200);
  EXPECT_EQ(spans[0].to_utime, 500);
  EXPECT_EQ(spans[0].scene, "a.nosound");
  EXPECT_EQ(spans[1].from_utime, 600);
  EXPECT_EQ(spans[1].to_utime, kMax);  // muted to the end, tail included

  const std::vector<MutedSpan> from_start = mutedSpans({}, "x.nosound", muted);
  ASSERT_EQ(from_start.size(), 1u);
  EXPECT_EQ(from_start[0].from_utime, kMin);
  EXPECT_TRUE(mutedSpans(hellos, "a", [](const std::string&) { return false; }).empty());
}

TEST(SceneMute, SilenceZeroesTheSamplesFromTheSwitchToTheNext) {
  std::vector<float> x(100, 1.0f);
  // 1000 Hz: a sample per ms; origin 1 s. [1.010 s, 1.0205 s): samples 10..20 (20.5 rounds up).
  const std::vector<MutedSpan> spans{{1'010'000, 1'020'500, "m"}, {1'090'000, kMax, "m"}};
  EXPECT_EQ(silenceMuted(x, spans, 1'000'000, 1000.0), 11u + 10u);
  for (std::size_t n = 0; n < x.size(); ++n)
    EXPECT_EQ(x[n], (n >= 10 && n <= 20) || n >= 90 ? 0.0f : 1.0f) << n;
  std::vector<float> y(10, 1.0f);
  EXPECT_EQ(silenceMuted(y, std::vector<MutedSpan>{{kMin, 500, "m"}}, 1'000'000, 1000.0), 0u);  // before the start
  EXPECT_EQ(silenceMuted(y, std::vector<MutedSpan>{{kMin, 1'003'000, "m"}}, 1'000'000, 1000.0), 3u);
}

constexpr double kRate = 48000.0;
constexpr std::int64_t kFirstTick = 1000;

// A small grooved scene and its muted twin; slab Tet10 4 x 4 x 1, no pen, no micro level.
struct MutedScenes {
  thx::test::TempDir dir{"scene_mute"};
  LiveSceneSettings settings;
  MutedScenes() {
    const std::string scene = "version: 1\nname: g\nsurface:\n  size: [0.2, 0.2]\n"
                              "  texture: {generator: grooves, size: 64, params: {extent: 0.2, period: 0.02, depth: 0.001}}\n"
                              "  representation: normal\n  material: steel\n";
    std::ofstream(dir.file("g.yaml")) << scene;
    std::ofstream(dir.file("g.nosound.yaml")) << scene << "audio: {mute: true}\n";
    settings.slab.cells = 4;
    settings.slab.modes = 10;
    settings.slab.sample_rate_hz = kRate;
    settings.slab.no_cache = true;
    settings.slab.quiet = true;
    settings.pen_modes = false;
    settings.micro = false;
    settings.max_block = 480;
  }
};

double peak(const std::vector<float>& x) {
  double p = 0.0;
  for (float v : x) p = std::max(p, double(std::fabs(v)));
  return p;
}

TEST(SceneMute, TheLiveClientPlaysZerosForAMutedSceneAndSoundAfterSwitchingBack) {
  MutedScenes s;
  test::SteppingClock clock;
  LiveSynth synth(LiveSynthOptions{.sample_rate_hz = kRate, .adapt_budget = false, .budget = {}}, clock);
  QueueSink sink(synth.queue());
  ExcitationFeed feed(sink);
  // The pen at 1 m/s over the grooves: a texel (3.125 mm) every 3.1 ticks, 10 ticks a batch.
  const std::vector<thx_msgs::contact_batch_t> batches = test::penBatches(kFirstTick, 300, 10, 1.0);
  std::size_t next_batch = 0;
  // One 10 ms block per batch, each batch fed before its block (lock-step, as test_live_pipeline).
  const auto play = [&](int blocks) {
    std::vector<float> out;
    std::vector<float> block(480);
    for (int k = 0; k < blocks; ++k, ++next_batch) {
      feed.contactBatch(batches.at(next_batch), 0);
      synth.process(block, (kFirstTick + 10 * std::int64_t(next_batch)) * 1'000'000);
      out.insert(out.end(), block.begin(), block.end());
      synth.collect();
    }
    return out;
  };
  // As runLive switches: the new scene's sources feed, its SynthScene is offered.
  std::vector<std::unique_ptr<LiveScene>> scenes;
  const auto switchTo = [&](const std::string& file, std::uint32_t generation) {
    scenes.push_back(buildLiveScene(s.dir.file(file), s.settings, generation));
    feed.setSources(scenes.back()->sourcePointers());
    synth.offerScene(std::move(scenes.back()->synth));
  };

  switchTo("g.yaml", 1);
  const std::vector<float> before = play(10);
  EXPECT_GT(peak(before), 0.0);
  EXPECT_NE(before.back(), 0.0f);  // still ringing when the switch comes
  EXPECT_GT(synth.counters().events.load(), 0u);

  switchTo("g.nosound.yaml", 2);
  EXPECT_TRUE(scenes.back()->sources.empty());  // nothing is excited on a muted scene
  const std::uint64_t events_before_mute = synth.counters().events.load();
  const std::vector<float> muted = play(10);
  for (std::size_t n = 0; n < muted.size(); ++n) ASSERT_EQ(muted[n], 0.0f) << "sample " << n;  // the ring is cut too
  EXPECT_EQ(synth.counters().events.load(), events_before_mute);
  EXPECT_TRUE(synth.sceneCurrent());

  switchTo("g.yaml", 3);
  const std::vector<float> after = play(10);
  EXPECT_GT(peak(after), 0.0);
  EXPECT_GT(synth.counters().events.load(), events_before_mute);
  EXPECT_EQ(synth.counters().scenes.load(), 3u);
}

}  // namespace
}  // namespace thx::audio::test_scene_mute
