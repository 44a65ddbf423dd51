// The live pipeline in lock-step, without the network: hapticd's CONTACT batches (recorded here
// as a straight scrape over grooves) through the feed and the pen's meso source into the queue,
// the callback (LiveSynth) on a virtual clock block by block, and its output against the offline
// render of the same ticks (renderScrape); then scene switches and lost batches.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "clients/audio/excitation_feed.hpp"
#include "clients/audio/live_synth.hpp"
#include "clients/audio/pen_meso_source.hpp"
#include "clients/audio/scrape_synthesis.hpp"
#include "tests/audio/live_fixtures.hpp"

namespace thx::audio {
namespace {

constexpr double kRate = 48000.0;  // 48 samples per servo tick: the tick times fall on samples
constexpr std::int64_t kFirstTick = 1000;
constexpr int kTicks = 500;

PenScrapeOptions penOptions() {
  PenScrapeOptions p;
  p.servo_hz = 1000.0;
  p.pen_mass_kg = 0.05;
  p.surface_size_m = {0.2, 0.2};
  return p;
}

struct Pipeline {
  tex::TextureMap map = test::grooveMap();
  test::SteppingClock clock;
  LiveSynth synth;
  QueueSink sink{synth.queue()};
  ExcitationFeed feed{sink};
  PenMesoSource pen;
  explicit Pipeline(LiveSynthOptions o = options())
      : synth(o, clock), pen(map, test::liveSlab().mesh, penOptions(), 1, /*playout_delay_ns=*/0) {
    feed.setSources({&pen});
    synth.offerScene(std::make_unique<SynthScene>(std::vector<SoundingBody>{test::liveSlab().body()}, kRate, 480, 1));
  }
  static LiveSynthOptions options() {
    LiveSynthOptions o;
    o.sample_rate_hz = kRate;
    o.adapt_budget = false;
    return o;
  }
};

TEST(LivePipeline, LockStepOutputEqualsTheOfflineRender) {
  Pipeline p;
  // Every batch of 10 ticks is received before the 10 ms block that plays them (block k starts at
  // tick kFirstTick + 10 k, on the clock the ticks' utime is on).
  const std::vector<thx_msgs::contact_batch_t> batches = test::penBatches(kFirstTick, kTicks, 10, 0.5);
  const int blocks = 100;  // 1 s: the scrape and half a second of ring-out
  std::vector<float> live(std::size_t(blocks) * 480);
  for (int k = 0; k < blocks; ++k) {
    if (std::size_t(k) < batches.size()) p.feed.contactBatch(batches[std::size_t(k)], 0);
    const std::int64_t start_ns = (kFirstTick + 10 * k) * 1'000'000;
    p.synth.process(std::span<float>(live).subspan(std::size_t(k) * 480, 480), start_ns);
  }
  EXPECT_EQ(p.feed.counters().samples, std::uint64_t(kTicks));
  EXPECT_EQ(p.synth.counters().late_events.load(), 0u);
  EXPECT_GT(p.synth.counters().events.load(), 0u);

  std::vector<ScrapeSample> path;
  for (const auto& b : batches)
    for (const auto& c : b.samples) path.push_back({c.tick, c.in_contact != 0, {c.uv[0], c.uv[1]}});
  ScrapeOptions so;
  so.sample_rate_hz = kRate;
  so.servo_hz = 1000.0;
  so.pen_mass_kg = 0.05;
  so.tail_s = 0.5;
  so.roughness.amplitude = 0.0;  // live plays the meso level only (no micro level yet)
  const ScrapeRender offline = renderScrape(p.map, test::liveSlab().mesh, test::liveSlab().modes, path, so);
  ASSERT_GT(offline.raw_peak, 0.0);
  EXPECT_EQ(p.pen.texels(), offline.impulses);

  // The offline render is normalised to a peak of so.peak; the live one is the raw sum.
  const std::size_t n = std::min(live.size(), offline.samples.size());
  ASSERT_GT(n, std::size_t(kRate * 0.9));
  double worst = 0.0;
  for (std::size_t i = 0; i < n; ++i)
    worst = std::max(worst, std::fabs(double(live[i]) - double(offline.samples[i]) * offline.raw_peak / so.peak));
  EXPECT_LT(worst, 1e-5 * offline.raw_peak) << "largest difference " << worst << " of a peak " << offline.raw_peak;
}

TEST(LivePipeline, ASceneSwitchDropsTheOldScenesEventsAndPlaysTheNewOnes) {
  Pipeline p;
  // At 1 m/s a texel (3.125 mm) every 3.1 ticks.
  const std::vector<thx_msgs::contact_batch_t> batches = test::penBatches(kFirstTick, 100, 10, 1.0);
  std::vector<float> block(480);
  // Scene 1's impulses for the first 50 ms are queued, but the first block plays only 10 ms.
  for (int k = 0; k < 5; ++k) p.feed.contactBatch(batches[std::size_t(k)], 0);
  p.synth.process(block, kFirstTick * 1'000'000);
  const std::uint64_t played_before = p.synth.counters().events.load();
  EXPECT_GT(played_before, 0u);
  EXPECT_GT(p.synth.queue().size(), 0u);

  // The switch, as the live client does it: scene 2's sources (generation 2) feed, its SynthScene
  // is offered. Scene 2 here is one mode only, so what plays shows which scene played it.
  tex::TextureMap map2 = test::grooveMap();
  PenMesoSource pen2(map2, test::liveSlab().mesh, penOptions(), 2, 0);
  p.feed.setSources({&pen2});
  SoundingBody one = test::liveSlab().body();
  one.frequency_hz.resize(1);
  one.decay_per_s.resize(1);
  one.shapes.conservativeResize(Eigen::NoChange, 1);
  // Scene 2's events queued before its scene reaches the callback wait for it (not dropped).
  for (int k = 5; k < 10; ++k) p.feed.contactBatch(batches[std::size_t(k)], 0);
  p.synth.process(block, (kFirstTick + 10) * 1'000'000);
  const std::uint64_t stale_before_offer = p.synth.counters().stale_events.load();
  const std::uint64_t played_before_offer = p.synth.counters().events.load();
  p.synth.offerScene(std::make_unique<SynthScene>(std::vector<SoundingBody>{one}, kRate, 480, 2));
  EXPECT_FALSE(p.synth.sceneCurrent());
  for (int k = 2; k < 10; ++k) p.synth.process(block, (kFirstTick + 10 * k) * 1'000'000);
  p.synth.collect();
  EXPECT_TRUE(p.synth.sceneCurrent());
  EXPECT_EQ(p.synth.counters().scenes.load(), 2u);
  // Scene 1's impulses still queued at the switch (those after 20 ms) were dropped, none played.
  EXPECT_GT(p.synth.counters().stale_events.load(), stale_before_offer);
  // Scene 2's impulses (ticks 50..99: its walk starts at tick 50) all played, on the one mode
  // (on the grooves every texel entered gives a non-zero impulse).
  EXPECT_GT(pen2.texels(), 0u);
  EXPECT_EQ(p.synth.counters().events.load() - played_before_offer, pen2.texels());
  EXPECT_EQ(p.synth.queue().size(), 0u);
  EXPECT_EQ(p.synth.counters().bad_events.load(), 0u);
  EXPECT_EQ(p.synth.counters().rendered_modes.load(), 1u);
}

TEST(LivePipeline, ALostBatchStartsANewWalkInsteadOfAnImpulseAcrossTheGap) {
  // At 0.1 m/s from u = 0.3 the tip enters texel 20, 21, 22 (of 64) at ticks 25.0, 56.25, 87.5
  // after the first. Straight through: 3 texels. With batch 5 (ticks 50..59) lost, the walk
  // restarts after the gap at tick 60, already in texel 21: the entry into it is not heard, and
  // no impulse is made across the gap.
  const std::vector<thx_msgs::contact_batch_t> batches = test::penBatches(kFirstTick, 100, 10, 0.1);
  Pipeline all, gap;
  for (const auto& b : batches) all.feed.contactBatch(b, 0);
  for (std::size_t k = 0; k < batches.size(); ++k)
    if (k != 5) gap.feed.contactBatch(batches[k], 0);
  EXPECT_EQ(gap.feed.counters().lost_batches, 1u);
  EXPECT_EQ(all.pen.texels(), 3u);
  EXPECT_EQ(gap.pen.texels(), 2u);
  const std::uint64_t walked_ticks_all = all.pen.ticks(), walked_ticks_gap = gap.pen.ticks();
  EXPECT_EQ(walked_ticks_all, 100u);
  EXPECT_EQ(walked_ticks_gap, 90u);
  // A duplicate batch (a resend) is ignored.
  all.feed.contactBatch(batches.back(), 0);
  EXPECT_EQ(all.feed.counters().samples, 100u);
  EXPECT_EQ(all.feed.counters().duplicates, 1u);
}

TEST(LivePipeline, ANewSubscriptionsBatchesArePlayedThoughTheirSeqStartsAgain) {
  // The kit asked for the stream again (a silence): hapticd's batches count from seq 1 again,
  // with newer ticks. They are played, after a restart of the walk.
  const std::vector<thx_msgs::contact_batch_t> first = test::penBatches(kFirstTick, 50, 10, 0.1);
  std::vector<thx_msgs::contact_batch_t> again = test::penBatches(kFirstTick, 100, 10, 0.1);
  again.erase(again.begin(), again.begin() + 5);  // ticks 50..99
  for (std::size_t k = 0; k < again.size(); ++k) again[k].seq = std::int64_t(k) + 1;
  Pipeline p;
  for (const auto& b : first) p.feed.contactBatch(b, 0);
  for (const auto& b : again) p.feed.contactBatch(b, 0);
  EXPECT_EQ(p.feed.counters().samples, 100u);
  EXPECT_EQ(p.feed.counters().resubscriptions, 1u);
  EXPECT_EQ(p.feed.counters().duplicates, 0u);
  // The walk restarted at tick 50 (before texel 21's entry at 56.25): all 3 texels are heard.
  EXPECT_EQ(p.pen.texels(), 3u);
}

}  // namespace
}  // namespace thx::audio
