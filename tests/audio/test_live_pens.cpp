// Every pen live (issue 30): two devices' CONTACT batches, interleaved as hapticd sends them on one
// channel, through PenFeeds (one ExcitationFeed and PenSource per device, each pen a body of its
// own on the one slab) and the callback in lock-step. Modal synthesis is linear, so the two pens
// together must equal the sum of each pen played alone through the same scene, to float rounding;
// each device's feed counts its own batches and ticks. With only_device (--device N) the other
// pen's batches are skipped and counted, and the output is that pen's alone.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <vector>

#include "clients/audio/live/live_synth.hpp"
#include "clients/audio/live/pen_feeds.hpp"
#include "clients/audio/live/pen_source.hpp"
#include "tests/audio/live_fixtures.hpp"

namespace thx::audio::test_live_pens {
namespace {

constexpr double kRate = 48000.0;  // 48 samples per servo tick
constexpr std::int64_t kFirstTick = 1000;
constexpr int kTicks = 500, kBlocks = 100, kBlock = 480;

// Device `device`'s scrape: its own speed and force (so the two pens' paths differ).
std::vector<thx_msgs::contact_batch_t> deviceBatches(int device, double speed, double force_n) {
  std::vector<thx_msgs::contact_batch_t> out = test::penBatches(kFirstTick, kTicks, 10, speed, force_n);
  for (auto& b : out) {
    b.device = device;
    for (auto& c : b.samples) c.device = device;
  }
  return out;
}

RoughnessOptions roughness() {
  RoughnessOptions r;
  r.length = 1u << 12;
  return r;
}

PenScrapeOptions penOptions(double mass_kg) {
  PenScrapeOptions p;
  p.servo_hz = 1000.0;
  p.pen_mass_kg = mass_kg;
  p.surface_size_m = {0.2, 0.2};
  return p;
}

// The slab (body 0) and two pens (bodies 1, 2), each pen's source on its device's feed; the
// micro level on, played a tick late (1 ms playout delay) so no event is late.
struct TwoPens {
  tex::TextureMap map = test::grooveMap();
  test::SteppingClock clock;
  LiveSynth synth;
  QueueSink sink{synth.queue()};
  PenFeeds feeds;
  PenSource pen0, pen1;
  explicit TwoPens(std::optional<int> only_device)
      : synth(options(), clock),
        feeds(sink, only_device),
        pen0(map, test::liveSlab().mesh, penOptions(0.05), PenSourceBodies{1, test::livePen().tip, 30.0, true}, 1, 1'000'000),
        pen1(map, test::liveSlab().mesh, penOptions(0.08), PenSourceBodies{2, test::livePen().tip, 30.0, true}, 1, 1'000'000) {
    feeds.setPen(0, {&pen0});
    feeds.setPen(1, {&pen1});
    std::vector<SoundingBody> bodies{test::liveSlab().body(), test::livePen().body(), test::livePen().body()};
    synth.offerScene(std::make_unique<SynthScene>(std::move(bodies), kRate, kBlock, 1,
                                                  std::make_shared<const RoughnessProfile>(roughness())));
  }
  static LiveSynthOptions options() {
    LiveSynthOptions o;
    o.sample_rate_hz = kRate;
    o.adapt_budget = false;
    return o;
  }
  // Block k plays after batch k of each device in `devices` was received (device 1's first).
  std::vector<float> play(const std::vector<int>& devices) {
    const auto b0 = deviceBatches(0, 0.5, 1.0), b1 = deviceBatches(1, 0.3, 0.6);
    std::vector<float> out(std::size_t(kBlocks) * kBlock);
    for (int k = 0; k < kBlocks; ++k) {
      for (int d : devices)
        if (std::size_t(k) < b0.size()) feeds.contactBatch((d == 0 ? b0 : b1)[std::size_t(k)], 0);
      synth.process(std::span<float>(out).subspan(std::size_t(k) * kBlock, kBlock), (kFirstTick + 10 * k) * 1'000'000);
    }
    return out;
  }
};

double peak(const std::vector<float>& v) {
  double p = 0.0;
  for (float x : v) p = std::max(p, std::fabs(double(x)));
  return p;
}

// max |a - (b + c)| (c may be empty: |a - b|).
double largestDifference(const std::vector<float>& a, const std::vector<float>& b, const std::vector<float>& c = {}) {
  double worst = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i)
    worst = std::max(worst, std::fabs(double(a[i]) - double(b[i]) - (c.empty() ? 0.0 : double(c[i]))));
  return worst;
}

TEST(LivePens, TwoPensTogetherEqualTheSumOfEachAlone) {
  TwoPens both(std::nullopt), only0(std::nullopt), only1(std::nullopt);
  const std::vector<float> mix = both.play({1, 0});
  const std::vector<float> alone0 = only0.play({0});
  const std::vector<float> alone1 = only1.play({1});
  for (int d : {0, 1}) {
    EXPECT_EQ(both.feeds.counters(d).batches, 50u) << "device " << d;
    EXPECT_EQ(both.feeds.counters(d).samples, std::uint64_t(kTicks)) << "device " << d;
    EXPECT_EQ(both.feeds.counters(d).lost_batches, 0u) << "device " << d;  // each device's seq on its own
    EXPECT_EQ(both.feeds.counters(d).duplicates, 0u) << "device " << d;
  }
  EXPECT_EQ(both.feeds.total().samples, 2u * kTicks);
  EXPECT_EQ(both.feeds.total().other_device, 0u);
  EXPECT_EQ(both.pen0.microSegments(), std::uint64_t(kTicks - 1));
  EXPECT_EQ(both.pen1.microSegments(), std::uint64_t(kTicks - 1));
  EXPECT_EQ(both.pen0.texels(), only0.pen0.texels());
  EXPECT_EQ(both.pen1.texels(), only1.pen1.texels());
  EXPECT_GT(both.pen1.texels(), 0u);
  EXPECT_EQ(both.synth.counters().late_events.load(), 0u);
  EXPECT_EQ(both.synth.counters().bad_events.load(), 0u);
  EXPECT_EQ(both.synth.counters().events.load(),
            only0.synth.counters().events.load() + only1.synth.counters().events.load());

  const double p = peak(mix);
  ASSERT_GT(peak(alone0), 0.0);
  ASSERT_GT(peak(alone1), 0.0);
  const double worst = largestDifference(mix, alone0, alone1);
  std::printf("[measured] two pens: peaks %.3g (mix), %.3g, %.3g (alone); mix - sum largest %.3g of the mix's peak\n", p,
              peak(alone0), peak(alone1), worst / p);
  EXPECT_LT(worst, 1e-5 * p);
  // Both pens are heard: the mix is neither pen alone.
  EXPECT_GT(largestDifference(mix, alone0), 0.05 * p);
  EXPECT_GT(largestDifference(mix, alone1), 0.05 * p);
}

TEST(LivePens, OnlyDeviceOnePlaysPenOneAloneAndCountsTheOthers) {
  TwoPens one(1), alone(std::nullopt);
  const std::vector<float> out = one.play({0, 1});
  const std::vector<float> expected = alone.play({1});
  EXPECT_EQ(one.feeds.counters(0).batches, 0u);
  EXPECT_EQ(one.feeds.counters(1).samples, std::uint64_t(kTicks));
  EXPECT_EQ(one.feeds.total().other_device, 50u);
  EXPECT_EQ(one.pen0.texels(), 0u);
  ASSERT_GT(peak(expected), 0.0);
  EXPECT_EQ(largestDifference(out, expected), 0.0);  // the same events in the same order
}

}  // namespace
}  // namespace thx::audio::test_live_pens
