// probe-client's accounting (thx_client/stream_monitor.hpp) on hand-made arrivals.
#include <gtest/gtest.h>

#include "thx_client/stream_monitor.hpp"

namespace test_stream_monitor {

using thx::client::StreamMonitor;

TEST(StreamMonitor, RateLatencyGapsAndDuplicatesOfALatestValueStream) {
  StreamMonitor m(100.0);  // 10 ms apart
  std::int64_t tick = 0;
  for (int k = 0; k < 50; ++k, tick += 10) {
    if (k == 20 || k == 21 || k == 35) continue;      // lost: two gaps, 3 messages missing
    const std::int64_t utime = 1'000'000 + tick * 1000;  // µs
    m.onMessage(tick, utime, utime * 1000 + 300'000);    // received 300 µs later
    if (k == 40) m.onMessage(tick, utime, utime * 1000 + 400'000);  // the same tick again
  }
  const auto r = m.report();
  EXPECT_EQ(r.messages, 47u);
  EXPECT_EQ(r.duplicates, 1u);
  EXPECT_EQ(r.gaps, 2u);
  EXPECT_EQ(r.missing, 3u);
  EXPECT_NEAR(r.span_s, 0.49, 1e-9);
  EXPECT_NEAR(r.achieved_rate_hz, 46 / 0.49, 1e-6);
  EXPECT_NEAR(r.latency_p50_us, 300.0, 1e-6);
  EXPECT_NEAR(r.latency_max_us, 300.0, 1e-6);
}

TEST(StreamMonitor, BatchesAreCheckedBySequenceAndTicks) {
  StreamMonitor m(100.0);
  std::int64_t next_tick = 0;
  for (std::int64_t seq = 1; seq <= 10; ++seq) {
    thx_msgs::contact_batch_t b{};
    b.seq = seq;
    b.num_dropped = seq == 7 ? 2 : 0;  // the server lost two ticks before batch 7
    next_tick += b.num_dropped;
    for (int k = 0; k < 10; ++k) {
      thx_msgs::contact_t s{};
      s.tick = next_tick++;
      s.utime = s.tick * 1000;
      b.samples.push_back(s);
    }
    b.num_samples = 10;
    b.next_tick = next_tick;
    if (seq == 4) continue;  // lost in transit
    m.onBatch(b, next_tick * 1'000'000 + 500'000);
    if (seq == 5) m.onBatch(b, 0);  // delivered twice
  }
  const auto r = m.report();
  EXPECT_EQ(r.messages, 9u);
  EXPECT_EQ(r.duplicates, 1u);
  EXPECT_EQ(r.gaps, 1u);
  EXPECT_EQ(r.missing, 1u);
  EXPECT_EQ(r.samples, 90u);
  EXPECT_EQ(r.samples_missing, 10u);
  EXPECT_EQ(r.samples_dropped, 2u);
  EXPECT_EQ(r.samples_out_of_order, 0u);
  EXPECT_NEAR(r.latency_p50_us, 1500.0, 1e-6);  // newest sample's tick time -> receipt
}

TEST(StreamMonitor, AServerRestartIsNotADuplicate) {
  StreamMonitor m(100.0);
  auto batch = [](std::int64_t instance, std::int64_t seq, std::int64_t first_tick) {
    thx_msgs::contact_batch_t b{};
    b.server_instance = instance;
    b.seq = seq;
    for (std::int64_t t = first_tick; t < first_tick + 10; ++t) {
      thx_msgs::contact_t s{};
      s.tick = t;
      b.samples.push_back(s);
    }
    b.num_samples = 10;
    b.next_tick = first_tick + 10;
    return b;
  };
  m.onBatch(batch(1, 1, 0), 1);
  m.onBatch(batch(1, 2, 10), 2);
  m.onBatch(batch(2, 1, 0), 3);  // new instance: seq and ticks start again
  m.onBatch(batch(2, 2, 10), 4);
  const auto r = m.report();
  EXPECT_EQ(r.restarts, 1u);
  EXPECT_EQ(r.duplicates, 0u);
  EXPECT_EQ(r.samples, 40u);
  EXPECT_EQ(r.samples_missing, 0u);
}

}  // namespace test_stream_monitor
