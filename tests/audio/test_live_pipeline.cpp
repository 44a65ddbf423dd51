// The live pipeline in lock-step, without the network: hapticd's CONTACT batches (recorded here
// as a straight scrape over grooves, or over a relief's facet) through the feed and the pen's
// source into the queue, the callback (LiveSynth) on a virtual clock block by block, and its
// output against the offline render of the same ticks (renderScrape): meso level alone, then with
// the micro level and the pen's own modes, then on a relief; a physics impact and a rolling
// object's texel path against the offline physics render (renderPhysicsStreams); then scene
// switches and lost batches.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <vector>

#include "clients/audio/live/excitation_feed.hpp"
#include "clients/audio/live/live_scene.hpp"
#include "clients/audio/live/live_synth.hpp"
#include "clients/audio/live/pen_source.hpp"
#include "clients/audio/live/physics_source.hpp"
#include "clients/audio/offline/physics_sound.hpp"
#include "clients/audio/offline/scrape_synthesis.hpp"
#include "tests/audio/live_fixtures.hpp"
#include "tests/audio/physics_fixtures.hpp"

namespace thx::audio::test_live_pipeline {
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

// What the pipeline plays: the slab alone (meso only), or with the micro level and the pen's modes.
// A micro segment starts at the tick before the later one that brings it, so with the micro level
// the events are played a tick (48 samples) after the offline render places them: the batch of
// ticks t..t+9 then holds every event of the block from tick t.
struct PipelineSetup {
  bool pen = false, micro = false;
  MesoSource meso = MesoSource::TexelWalk;
  std::int64_t delay_ns() const { return micro ? 1'000'000 : 0; }
  std::size_t delay_samples() const { return micro ? 48 : 0; }
};

RoughnessOptions roughness() {
  RoughnessOptions r;  // the defaults (amplitude 0.03), a short table
  r.length = 1u << 12;
  return r;
}

struct Pipeline {
  tex::TextureMap map = test::grooveMap();
  test::SteppingClock clock;
  LiveSynth synth;
  QueueSink sink{synth.queue()};
  ExcitationFeed feed{sink};
  PenSource pen;
  explicit Pipeline(PipelineSetup setup = {}, LiveSynthOptions o = options())
      : synth(o, clock),
        pen(map, test::liveSlab().mesh, penOptions(setup.meso),
            PenSourceBodies{setup.pen ? 1 : -1, test::livePen().tip, 30.0, setup.micro}, 1, setup.delay_ns()) {
    feed.setSources({&pen});
    std::vector<SoundingBody> bodies{test::liveSlab().body()};
    if (setup.pen) bodies.push_back(test::livePen().body());
    synth.offerScene(std::make_unique<SynthScene>(std::move(bodies), kRate, 480, 1,
                                                  setup.micro ? std::make_shared<const RoughnessProfile>(roughness()) : nullptr));
  }
  static PenScrapeOptions penOptions(MesoSource meso) {
    PenScrapeOptions p = test_live_pipeline::penOptions();
    p.meso = meso;
    return p;
  }
  static LiveSynthOptions options() {
    LiveSynthOptions o;
    o.sample_rate_hz = kRate;
    o.adapt_budget = false;
    return o;
  }
};

// Every batch of 10 ticks is received before the 10 ms block that plays them (block k starts at
// tick kFirstTick + 10 k, on the clock the ticks' utime is on); 1 s: the scrape and half a
// second of ring-out.
std::vector<float> playLockStep(Pipeline& p, const std::vector<thx_msgs::contact_batch_t>& batches) {
  const int blocks = 100;
  std::vector<float> live(std::size_t(blocks) * 480);
  for (int k = 0; k < blocks; ++k) {
    if (std::size_t(k) < batches.size()) p.feed.contactBatch(batches[std::size_t(k)], 0);
    const std::int64_t start_ns = (kFirstTick + 10 * k) * 1'000'000;
    p.synth.process(std::span<float>(live).subspan(std::size_t(k) * 480, 480), start_ns);
  }
  return live;
}

// The offline render of the same ticks, denormalised (renderScrape normalises to a peak of
// so.peak; the live output is the raw sum).
struct Offline {
  ScrapeRender render;
  std::vector<double> raw;
};
Offline renderOffline(const Pipeline& p, const std::vector<thx_msgs::contact_batch_t>& batches, const PipelineSetup& setup) {
  std::vector<ScrapeSample> path;
  for (const auto& b : batches)
    for (const auto& c : b.samples) path.push_back(scrapeSample(c));
  ScrapeOptions so;
  so.sample_rate_hz = kRate;
  so.servo_hz = 1000.0;
  so.pen_mass_kg = 0.05;
  so.tail_s = 0.5;
  so.meso = setup.meso;
  so.roughness = roughness();
  if (!setup.micro) so.roughness.amplitude = 0.0;
  const PenModes pen{&test::livePen().mesh, &test::livePen().modes, test::livePen().tip, 30.0};
  Offline o;
  o.render = renderScrape(p.map, test::liveSlab().mesh, test::liveSlab().modes, path, so, setup.pen ? &pen : nullptr);
  for (float x : o.render.samples) o.raw.push_back(double(x) * o.render.raw_peak / so.peak);
  return o;
}

// live[i + delay] against offline[i]; live's first `delay` samples must be silent.
double largestDifference(const std::vector<float>& live, const std::vector<double>& offline, std::size_t delay = 0) {
  const std::size_t n = std::min(live.size() - delay, offline.size());
  EXPECT_GT(n, std::size_t(kRate * 0.85));
  double worst = 0.0;
  for (std::size_t i = 0; i < delay; ++i) worst = std::max(worst, std::fabs(double(live[i])));
  for (std::size_t i = 0; i < n; ++i) worst = std::max(worst, std::fabs(double(live[i + delay]) - offline[i]));
  return worst;
}

TEST(LivePipeline, LockStepOutputEqualsTheOfflineRender) {
  Pipeline p;
  const std::vector<thx_msgs::contact_batch_t> batches = test::penBatches(kFirstTick, kTicks, 10, 0.5);
  const std::vector<float> live = playLockStep(p, batches);
  EXPECT_EQ(p.feed.counters().samples, std::uint64_t(kTicks));
  EXPECT_EQ(p.synth.counters().late_events.load(), 0u);
  EXPECT_GT(p.synth.counters().events.load(), 0u);

  const Offline offline = renderOffline(p, batches, {});
  ASSERT_GT(offline.render.raw_peak, 0.0);
  EXPECT_EQ(p.pen.texels(), offline.render.impulses);
  const double worst = largestDifference(live, offline.raw);
  std::printf("[measured] lock-step: largest difference %.3g of the peak\n", worst / offline.render.raw_peak);
  EXPECT_LT(worst, 1e-5 * offline.render.raw_peak) << "largest difference " << worst << " of a peak " << offline.render.raw_peak;
}

TEST(LivePipeline, LockStepWithTheMicroLevelAndThePensModesEqualsTheOfflineRender) {
  // Pressing with 1 N (growing): the micro level's force on every sample in contact, on the slab
  // and on the pen's tip, and the grooves' meso impulses on both.
  const PipelineSetup setup{true, true, MesoSource::TexelWalk};
  Pipeline p(setup);
  const std::vector<thx_msgs::contact_batch_t> batches = test::penBatches(kFirstTick, kTicks, 10, 0.5, 1.0);
  const std::vector<float> live = playLockStep(p, batches);
  EXPECT_EQ(p.synth.counters().late_events.load(), 0u);
  EXPECT_EQ(p.synth.counters().bad_events.load(), 0u);
  EXPECT_EQ(p.pen.microSegments(), std::uint64_t(kTicks - 1));

  const Offline offline = renderOffline(p, batches, setup);
  ASSERT_GT(offline.render.pen_peak, 0.0);
  ASSERT_GT(offline.render.micro_rms_n, 0.0);
  EXPECT_EQ(p.pen.texels(), offline.render.impulses);
  const double worst = largestDifference(live, offline.raw, setup.delay_samples());
  std::printf("[measured] lock-step: largest difference %.3g of the peak\n", worst / offline.render.raw_peak);
  EXPECT_LT(worst, 1e-5 * offline.render.raw_peak) << "largest difference " << worst << " of a peak " << offline.render.raw_peak;
  // The micro level and the pen are heard: the meso level on the slab alone differs.
  const Offline meso = renderOffline(p, batches, {});
  EXPECT_GT(largestDifference(live, meso.raw, setup.delay_samples()), 0.01 * offline.render.raw_peak);
}

TEST(LivePipeline, LockStepOnAReliefEqualsTheOfflineRender) {
  // A relief: the contact normal steps onto a 20-degree facet for 100 ticks and back (two
  // impulses, on the slab and the pen), with the micro level.
  const PipelineSetup setup{true, true, MesoSource::ContactNormals};
  Pipeline p(setup);
  std::vector<thx_msgs::contact_batch_t> batches = test::penBatches(kFirstTick, kTicks, 10, 0.1, 0.5);
  const double a = 20.0 * std::numbers::pi / 180.0;
  for (auto& b : batches)
    for (auto& c : b.samples)
      if (c.tick >= kFirstTick + 100 && c.tick < kFirstTick + 200) {
        c.n_sampled_world[0] = std::sin(a);
        c.n_sampled_world[2] = std::cos(a);
      }
  const std::vector<float> live = playLockStep(p, batches);
  EXPECT_EQ(p.synth.counters().late_events.load(), 0u);
  const Offline offline = renderOffline(p, batches, setup);
  EXPECT_EQ(offline.render.nonzero_impulses, 2u);
  EXPECT_EQ(p.pen.texels(), offline.render.impulses);
  const double worst = largestDifference(live, offline.raw, setup.delay_samples());
  std::printf("[measured] lock-step: largest difference %.3g of the peak\n", worst / offline.render.raw_peak);
  EXPECT_LT(worst, 1e-5 * offline.render.raw_peak) << "largest difference " << worst << " of a peak " << offline.render.raw_peak;
}

TEST(LivePipeline, LockStepPhysicsImpactsAndTexelPathsEqualTheOfflineRender) {
  // The physics client's streams: the 10 cm steel ball's pose, two impacts on the slab (each on
  // both bodies' modes, Hertz pulse factors), its texel path into and out of a tilted texel (Eq. 5
  // on both bodies), through the feed and PhysicsSource into the callback, against
  // renderPhysicsStreams of the same streams (origin utime 0 = the first block's start).
  const SoundingScene& sc = test::testScene();
  ASSERT_GT(sc.objects.at(0)->size(), 0u);
  constexpr double fs = 44100.0;
  test::SteppingClock clock;
  LiveSynthOptions o;
  o.sample_rate_hz = fs;
  o.adapt_budget = false;
  LiveSynth synth(o, clock);
  QueueSink sink(synth.queue());
  ExcitationFeed feed(sink);
  PhysicsSource source(sc, {1}, 1, 0);
  feed.setSources({&source});
  synth.offerScene(std::make_unique<SynthScene>(
      std::vector<SoundingBody>{soundingBody("surface", sc.surface->modes()), soundingBody("ball", sc.objects[0]->modes())}, fs,
      441, 1));

  const Eigen::Vector3d flat(0, 0, 1), tilted = Eigen::Vector3d(std::sin(0.3), 0, std::cos(0.3));
  PhysicsStreams streams;
  streams.poses.push_back(test::ballPose(0));
  streams.impacts.push_back(test::impact(20'000, 0.5));
  streams.contacts.push_back(test::pathMessage(101'000, 0.101, {flat, tilted}, 0));
  streams.contacts.push_back(test::pathMessage(102'000, 0.102, {tilted, flat}, 2));
  streams.impacts.push_back(test::impact(250'000, 2.0));
  // Delivered as the physics client sends them, in time order, before the block they sound in.
  feed.physicsPoses(streams.poses[0], 0);
  const int blocks = 60;  // 0.6 s of 10 ms blocks
  std::vector<float> live(std::size_t(blocks) * 441);
  for (int k = 0; k < blocks; ++k) {
    if (k == 1) feed.physicsImpact(streams.impacts[0], 0);
    if (k == 9)
      for (const auto& m : streams.contacts) feed.physicsContacts(m, 0);
    if (k == 24) feed.physicsImpact(streams.impacts[1], 0);
    synth.process(std::span<float>(live).subspan(std::size_t(k) * 441, 441), std::int64_t(k) * 10'000'000);
  }
  EXPECT_EQ(source.counts().impacts, 2u);
  EXPECT_EQ(source.counts().meso_impulses, 2u);
  EXPECT_EQ(synth.counters().events.load(), 8u);  // every excitation on both bodies
  EXPECT_EQ(synth.counters().late_events.load(), 0u);
  EXPECT_EQ(synth.counters().bad_events.load(), 0u);

  PhysicsSoundOptions po;
  po.sample_rate_hz = fs;
  po.tail_s = 0.5;
  const PhysicsRender offline = renderPhysicsStreams(streams, sc, [&](const std::string&) { return sc; }, 0, po);
  EXPECT_EQ(offline.strikes, 8u);
  double peak = 0.0, worst = 0.0;
  for (double x : offline.samples) peak = std::max(peak, std::fabs(x));
  ASSERT_GT(peak, 0.0);
  const std::size_t n = std::min(live.size(), offline.samples.size());
  ASSERT_GT(n, std::size_t(0.5 * fs));
  for (std::size_t i = 0; i < n; ++i) worst = std::max(worst, std::fabs(double(live[i]) - offline.samples[i]));
  std::printf("[measured] physics lock-step: largest difference %.3g of the peak\n", worst / peak);
  EXPECT_LT(worst, 1e-5 * peak) << "largest difference " << worst << " of a peak " << peak;
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
  PenSource pen2(map2, test::liveSlab().mesh, penOptions(), PenSourceBodies{}, 2, 0);
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
}  // namespace thx::audio::test_live_pipeline
