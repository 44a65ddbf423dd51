// Continuity checks on a channel that carries several devices' messages (protocol 6, issue 30):
// each device has its own batch seq and shares the servo's ticks with the others, so batch 5 of
// device 0 and batch 5 of device 1 are both new. probe-client's StreamMonitor judges each message
// against its own device's previous one; the live audio client's ExcitationFeed plays the one pen
// it follows and skips the others' batches before judging. Neither counts another device's
// messages as gaps or duplicates; a real gap is counted once, for its device.
#include <gtest/gtest.h>

#include <cstdint>
#include <ostream>
#include <utility>
#include <vector>

#include "clients/audio/live/excitation_feed.hpp"
#include "tests/clients/device_messages.hpp"
#include "thx_client/stream_monitor.hpp"

namespace test_device_gaps {

using thx::client::StreamMonitor;
using thx::test::contactBatch;

namespace {

// Batch `seq` of `device` covering ticks 10·(seq − 1) ..: both devices' batch k cover the same ticks.
thx_msgs::contact_batch_t batch(int device, std::int64_t seq, std::int64_t instance = 11) {
  return contactBatch(device, seq, (seq - 1) * 10, instance);
}
// Received 0.5 ms after its newest sample's tick.
std::int64_t receipt(const thx_msgs::contact_batch_t& b) { return b.samples.back().utime * 1000 + 500'000; }

// What a report's continuity checks counted, compared in one line.
struct Counts {
  std::uint64_t messages = 0, duplicates = 0, gaps = 0, missing = 0, samples_missing = 0, restarts = 0;
  bool operator==(const Counts&) const = default;
};
Counts countsOf(const thx::client::StreamReport& r) {
  return {r.messages, r.duplicates, r.gaps, r.missing, r.samples_missing, r.restarts};
}
std::ostream& operator<<(std::ostream& os, const Counts& c) {
  return os << "messages " << c.messages << ", duplicates " << c.duplicates << ", gaps " << c.gaps << ", missing "
            << c.missing << ", samples_missing " << c.samples_missing << ", restarts " << c.restarts;
}

}  // namespace

TEST(StreamMonitorDevices, TwoDevicesBatchesWithTheirOwnSeqAreNeitherGapsNorDuplicates) {
  StreamMonitor m(100.0);
  for (std::int64_t seq = 1; seq <= 3; ++seq) {
    for (int device : {0, 1}) m.onBatch(batch(device, seq), receipt(batch(device, seq)));
  }
  const auto r = m.report();
  EXPECT_EQ(countsOf(r), (Counts{.messages = 6}));  // no duplicate, gap or restart
  EXPECT_EQ(r.samples, 60u);
  EXPECT_EQ(r.samples_out_of_order, 0u);
  EXPECT_EQ(r.by_device[0].messages, 3u);
  EXPECT_EQ(r.by_device[1].messages, 3u);
  EXPECT_EQ(r.by_device[2].messages, 0u);
  EXPECT_NEAR(r.latency_p50_us, 500.0, 1e-6);
}

TEST(StreamMonitorDevices, AGapOnOneDeviceIsCountedOnceForThatDevice) {
  StreamMonitor m(100.0);
  for (std::int64_t seq = 1; seq <= 3; ++seq) {
    m.onBatch(batch(0, seq), receipt(batch(0, seq)));
    if (seq != 2) m.onBatch(batch(1, seq), receipt(batch(1, seq)));  // device 1's batch 2 lost
  }
  m.onBatch(batch(0, 3), receipt(batch(0, 3)));  // device 0's batch 3 again
  const auto r = m.report();
  // One duplicate (device 0's), one gap of one batch (device 1's ticks 10..19).
  EXPECT_EQ(countsOf(r), (Counts{.messages = 5, .duplicates = 1, .gaps = 1, .missing = 1, .samples_missing = 10}));
  EXPECT_EQ(r.by_device[1].gaps, 1u);
  EXPECT_EQ(r.by_device[1].missing, 1u);
  EXPECT_EQ(r.by_device[1].duplicates, 0u);
  EXPECT_EQ(r.by_device[0].gaps, 0u);
  EXPECT_EQ(r.by_device[0].duplicates, 1u);
}

TEST(StreamMonitorDevices, LatestValueMessagesOfTwoDevicesShareTicks) {
  StreamMonitor m(100.0);  // 10 ms apart, each device
  for (std::int64_t k = 0; k < 10; ++k) {
    for (int device : {0, 1}) {
      if (device == 0 && k == 5) continue;  // device 0's message of tick 50 lost
      m.onMessage(k * 10, k * 10'000, k * 10'000'000 + 300'000, device);
    }
  }
  const auto r = m.report();
  // Device 1's tick 40 after device 0's tick 40 is not older: no duplicate.
  EXPECT_EQ(countsOf(r), (Counts{.messages = 19, .gaps = 1, .missing = 1}));
  EXPECT_EQ(r.by_device[0].gaps, 1u);
  EXPECT_EQ(r.by_device[1].gaps, 0u);
  EXPECT_EQ(r.by_device[0].messages, 9u);
  EXPECT_EQ(r.by_device[1].messages, 10u);
}

TEST(StreamMonitorDevices, ARestartStartsEveryDeviceAgain) {
  StreamMonitor m(100.0);
  for (std::int64_t seq = 1; seq <= 2; ++seq) {
    for (int device : {0, 1}) m.onBatch(batch(device, seq, 1), receipt(batch(device, seq)));
  }
  for (int device : {1, 0}) m.onBatch(batch(device, 1, 2), 1'000'000'000);  // a new hapticd: seq and ticks from 1 and 0
  EXPECT_EQ(countsOf(m.report()), (Counts{.messages = 6, .restarts = 1}));
}

TEST(StreamMonitorDevices, AnIndexOutsideTheTableIsCountedNotJudged) {
  StreamMonitor m(100.0);
  m.onMessage(10, 10'000, 10'300'000, 0);
  m.onMessage(10, 10'000, 10'300'000, thx::client::kMaxDevices);
  m.onMessage(10, 10'000, 10'300'000, -1);
  m.onBatch(batch(99, 1), receipt(batch(99, 1)));
  const auto r = m.report();
  EXPECT_EQ(r.outside_devices, 3u);
  EXPECT_EQ(r.messages, 1u);
  EXPECT_EQ(r.duplicates, 0u);
  EXPECT_EQ(r.samples, 0u);
}

namespace {

// What the feed hands the scene's sources: each pen sample (device, tick) and each discontinuity.
class RecordingSource final : public thx::audio::ExcitationSource {
 public:
  void penContact(const thx_msgs::contact_t& c, std::int64_t, thx::audio::ExcitationSink&) override {
    played.emplace_back(c.device, c.tick);
  }
  void discontinuity() override { ++discontinuities; }
  std::vector<std::pair<int, std::int64_t>> played;
  int discontinuities = 0;
};

class NullSink final : public thx::audio::ExcitationSink {
 public:
  void push(const thx::audio::ExcitationEvent&) override {}
};

// Device `device`'s ticks first .. first + n - 1, as the sources should see them.
std::vector<std::pair<int, std::int64_t>> ticksOf(int device, std::int64_t first, std::int64_t n) {
  std::vector<std::pair<int, std::int64_t>> out;
  for (std::int64_t t = first; t < first + n; ++t) out.emplace_back(device, t);
  return out;
}

}  // namespace

TEST(ExcitationFeedDevices, PlaysTheFollowedPenOnlyWithoutGapsOrDuplicates) {
  for (int followed : {0, 1}) {
    NullSink sink;
    RecordingSource source;
    thx::audio::ExcitationFeed feed(sink, followed);
    feed.addSource(&source);
    for (std::int64_t seq = 1; seq <= 3; ++seq) {
      for (int device : {0, 1}) feed.contactBatch(batch(device, seq), 0);
    }
    const thx::audio::FeedCounters& c = feed.counters();
    EXPECT_EQ(c.batches, 3u) << followed;
    EXPECT_EQ(c.samples, 30u) << followed;
    EXPECT_EQ(c.other_device, 3u) << followed;
    EXPECT_EQ(c.lost_batches, 0u) << followed;
    EXPECT_EQ(c.duplicates, 0u) << followed;
    EXPECT_EQ(c.resubscriptions, 0u) << followed;
    EXPECT_EQ(c.restarts, 0u) << followed;
    EXPECT_EQ(source.discontinuities, 0) << followed;
    EXPECT_EQ(source.played, ticksOf(followed, 0, 30)) << followed;  // every tick once, one pen
  }
}

TEST(ExcitationFeedDevices, AGapOnTheFollowedPenIsOneLossAndAnotherPensIsNone) {
  NullSink sink;
  RecordingSource source;
  thx::audio::ExcitationFeed feed(sink);  // device 0
  feed.addSource(&source);
  for (std::int64_t seq : {1, 2, 4}) feed.contactBatch(batch(0, seq), 0);  // device 0's batch 3 lost
  for (std::int64_t seq : {1, 3}) feed.contactBatch(batch(1, seq), 0);     // device 1's batch 2 lost
  const thx::audio::FeedCounters& c = feed.counters();
  EXPECT_EQ(c.lost_batches, 1u);
  EXPECT_EQ(source.discontinuities, 1);
  EXPECT_EQ(c.other_device, 2u);
  EXPECT_EQ(c.duplicates, 0u);
  EXPECT_EQ(c.batches, 3u);
  std::vector<std::pair<int, std::int64_t>> expected = ticksOf(0, 0, 20);
  const auto after_gap = ticksOf(0, 30, 10);
  expected.insert(expected.end(), after_gap.begin(), after_gap.end());
  EXPECT_EQ(source.played, expected);
}

}  // namespace test_device_gaps
