// hapticd's subscription bookkeeping (server/subscriptions.hpp), driven by hand: a fake clock for
// heartbeats, tick numbers for rates, a recording sink instead of LCM. No network, no threads.
#include <gtest/gtest.h>

#include <cmath>
#include <thx_msgs/protocol.hpp>

#include "recording_sink.hpp"
#include "server/subscriptions.hpp"

namespace test_subscriptions {

using namespace thx;
using test::request;
using test::runTicks;

namespace {
constexpr std::int64_t kSec = 1'000'000'000;
using Req = thx_msgs::subscribe_request_t;

srv::SubscriptionLimits limits() {
  srv::SubscriptionLimits l;
  l.servo_rate_hz = 1000.0;
  l.max_rate_hz = 1000.0;
  l.max_clients = 4;
  l.max_bandwidth_bytes_per_s = 2e6;
  l.heartbeat_timeout_ns = 2 * kSec;
  l.server_instance = 77;
  return l;
}
}  // namespace

TEST(Subscriptions, GrantsAsAskedAndAnswersEveryField) {
  srv::SubscriptionTable t(limits());
  const auto r = t.handleRequest(request("visual", "DEVICE_STATE", 60.0, false, 5), 0);
  EXPECT_TRUE(r.accepted) << r.reason;
  EXPECT_EQ(r.reason, "");
  EXPECT_EQ(r.server_instance, 77);
  EXPECT_EQ(r.request_seq, 5);
  EXPECT_EQ(r.client_id, "visual");
  EXPECT_EQ(r.stream, "DEVICE_STATE");
  EXPECT_EQ(r.action, Req::ACTION_SUBSCRIBE);
  EXPECT_DOUBLE_EQ(r.rate_hz, 60.0);
  EXPECT_EQ(r.channel, "THX_DEVICE_STATE.visual");
  EXPECT_EQ(r.heartbeat_timeout_us, 2'000'000);
  EXPECT_EQ(t.numClients(), 1);
  EXPECT_TRUE(t.wantsTicks());

  const auto b = t.handleRequest(request("audio", "CONTACT", 100.0, true), 0);
  EXPECT_TRUE(b.accepted) << b.reason;
  EXPECT_TRUE(b.batch);
  EXPECT_EQ(b.channel, "THX_CONTACT_BATCH.audio");
}

TEST(Subscriptions, RatesAreMetOnAverageWithWholeTickIntervals) {
  srv::SubscriptionTable t(limits());
  for (double hz : {1000.0, 250.0, 60.0, 7.0}) {
    const std::string id = "c" + std::to_string(int(hz));
    ASSERT_TRUE(t.handleRequest(request(id, "DEVICE_STATE", hz), 0).accepted);
  }
  test::RecordingSink sink;
  runTicks(t, sink, 0, 6000);  // 6 s of servo ticks
  EXPECT_EQ(sink.statesOn("THX_DEVICE_STATE.c1000"), 6000u);
  EXPECT_EQ(sink.statesOn("THX_DEVICE_STATE.c250"), 1500u);
  EXPECT_EQ(sink.statesOn("THX_DEVICE_STATE.c60"), 360u);
  EXPECT_EQ(sink.statesOn("THX_DEVICE_STATE.c7"), 42u);
  // 60 Hz of 1 kHz: intervals of 16 or 17 ticks, never a burst.
  std::int64_t prev = -1;
  for (const auto& s : sink.states) {
    if (s.channel != "THX_DEVICE_STATE.c60") continue;
    if (prev >= 0) {
      EXPECT_GE(s.tick - prev, 16);
      EXPECT_LE(s.tick - prev, 17);
    }
    prev = s.tick;
  }
}

TEST(Subscriptions, RatesAboveTheLimitAreGrantedTheLimitWithAReason) {
  srv::SubscriptionLimits l = limits();
  l.max_rate_hz = 250.0;
  srv::SubscriptionTable t(l);
  auto r = t.handleRequest(request("a", "CONTACT", 5000.0), 0);
  EXPECT_TRUE(r.accepted);
  EXPECT_DOUBLE_EQ(r.rate_hz, 250.0);
  EXPECT_NE(r.reason.find("asked 5000 Hz, granted 250 Hz"), std::string::npos) << r.reason;
  EXPECT_NE(r.reason.find("--max-rate"), std::string::npos) << r.reason;

  r = t.handleRequest(request("a", "SERVO_STATS", 10.0), 0);
  EXPECT_DOUBLE_EQ(r.rate_hz, 1.0);
  EXPECT_NE(r.reason.find("SERVO_STATS window"), std::string::npos) << r.reason;

  // A batch must fit one datagram: 164 samples at most, so at least 1000/164 Hz.
  r = t.handleRequest(request("b", "CONTACT", 1.0, true), 0);
  EXPECT_TRUE(r.accepted);
  const double floor_hz = 1000.0 / double(thx_msgs::max_unfragmented_batch_samples(r.channel.size()));
  EXPECT_DOUBLE_EQ(r.rate_hz, floor_hz);
  EXPECT_NE(r.reason.find("one UDP datagram"), std::string::npos) << r.reason;
}

TEST(Subscriptions, RefusalsAreClearAndChangeNothing) {
  srv::SubscriptionTable t(limits());
  struct Case {
    Req req;
    const char* expect;
  };
  Req bad_action = request("a", "CONTACT", 10);
  bad_action.action = 9;
  const Case cases[] = {
      {request("bad id!", "CONTACT", 10), "invalid client_id 'bad id!'"},
      {request(std::string(33, 'x'), "CONTACT", 10), "invalid client_id"},
      {request("a", "FORCES", 10), "unknown stream 'FORCES'"},
      {request("a", "DEVICE_STATE", 10, true), "batching is only available for CONTACT, not DEVICE_STATE"},
      {request("a", "CONTACT", 0.0), "rate_hz must be a finite number > 0, got 0"},
      {request("a", "CONTACT", -5.0), "got -5"},
      {request("a", "CONTACT", std::nan("")), "got nan"},
      {request("a", "CONTACT", INFINITY), "got inf"},
      {bad_action, "unknown action 9"},
  };
  for (const Case& c : cases) {
    const auto r = t.handleRequest(c.req, 0);
    EXPECT_FALSE(r.accepted) << c.expect;
    EXPECT_NE(r.reason.find(c.expect), std::string::npos) << r.reason;
    EXPECT_EQ(r.channel, "");
    EXPECT_EQ(r.rate_hz, 0.0);
    EXPECT_LT(r.reason.size(), thx_msgs::kMaxTextLength);
  }
  EXPECT_EQ(t.numClients(), 0);
  EXPECT_FALSE(t.wantsTicks());
  EXPECT_EQ(t.counters().refused, std::size(cases));
}

TEST(Subscriptions, TooManyClientsIsRefusedUntilOneLeaves) {
  srv::SubscriptionTable t(limits());  // 4 clients
  for (int k = 0; k < 4; ++k) ASSERT_TRUE(t.handleRequest(request("c" + std::to_string(k), "SERVO_STATS", 1), 0).accepted);
  auto r = t.handleRequest(request("c4", "SERVO_STATS", 1), 0);
  EXPECT_FALSE(r.accepted);
  EXPECT_NE(r.reason.find("too many clients: 4 connected, the limit is 4 (hapticd --max-clients)"), std::string::npos)
      << r.reason;
  // A known client may add streams.
  EXPECT_TRUE(t.handleRequest(request("c0", "DEVICE_STATE", 10), 0).accepted);
  Req unsub = request("c1", "SERVO_STATS", 1);
  unsub.action = Req::ACTION_UNSUBSCRIBE;
  r = t.handleRequest(unsub, 0);
  EXPECT_TRUE(r.accepted);
  EXPECT_EQ(r.channel, "");
  EXPECT_EQ(t.numClients(), 3);
  EXPECT_TRUE(t.handleRequest(request("c4", "SERVO_STATS", 1), 0).accepted);
}

TEST(Subscriptions, BandwidthLimitRefusesWhatWouldExceedIt) {
  srv::SubscriptionTable t(limits());  // 2 MB/s
  // A full-rate batch costs ~394 kB/s of samples, a full-rate device state ~260 kB/s: three
  // batches and two device states fit in 2 MB/s, the third device state does not.
  int granted = 0;
  thx_msgs::subscribe_reply_t last;
  for (int k = 0; k < 3; ++k) {
    last = t.handleRequest(request("a" + std::to_string(k), "CONTACT", 1000.0, true), 0);
    granted += last.accepted;
  }
  for (int k = 0; k < 4 && last.accepted; ++k) {
    last = t.handleRequest(request("a" + std::to_string(k), "DEVICE_STATE", 1000.0), 0);
    granted += last.accepted;
  }
  ASSERT_FALSE(last.accepted);
  EXPECT_NE(last.reason.find("bandwidth limit: this subscription needs"), std::string::npos) << last.reason;
  EXPECT_NE(last.reason.find("of 2000 kB/s are in use (hapticd --max-bandwidth)"), std::string::npos) << last.reason;
  EXPECT_LE(t.bandwidth(), 2e6);
  // A replacement is measured without what it replaces, so asking again is not refused.
  EXPECT_TRUE(t.handleRequest(request("a0", "CONTACT", 1000.0, true), 0).accepted);
  EXPECT_EQ(granted, 5);
}

TEST(Subscriptions, WithoutAGraceSilentClientsAreForgottenAtTheHeartbeatTimeout) {
  srv::SubscriptionLimits l = limits();  // 2 s
  l.client_grace_ns = 0;
  srv::SubscriptionTable t(l);
  ASSERT_TRUE(t.handleRequest(request("alive", "DEVICE_STATE", 100), 0).accepted);
  ASSERT_TRUE(t.handleRequest(request("silent", "DEVICE_STATE", 100), 0).accepted);
  thx_msgs::heartbeat_t hb{};
  hb.client_id = "alive";
  for (std::int64_t now = 0; now <= 5 * kSec; now += kSec / 2) {
    EXPECT_TRUE(t.heartbeat(hb, now));
    const auto gone = t.expire(now);
    if (now <= 2 * kSec) {
      EXPECT_TRUE(gone.empty()) << now;  // exactly the timeout is still alive
    } else if (now == 2 * kSec + kSec / 2) {
      ASSERT_EQ(gone.size(), 1u);
      EXPECT_EQ(gone[0], "silent");
    }
  }
  EXPECT_EQ(t.numClients(), 1);
  EXPECT_EQ(t.counters().expired_clients, 1u);
  // The forgotten client's stream stopped; its heartbeats are now unknown.
  test::RecordingSink sink;
  runTicks(t, sink, 0, 100);
  EXPECT_EQ(sink.statesOn("THX_DEVICE_STATE.silent"), 0u);
  EXPECT_EQ(sink.statesOn("THX_DEVICE_STATE.alive"), 10u);
  hb.client_id = "silent";
  EXPECT_FALSE(t.heartbeat(hb, 6 * kSec));
  EXPECT_EQ(t.counters().unknown_heartbeats, 1u);
  // A request is a sign of life too.
  EXPECT_TRUE(t.handleRequest(request("alive", "DEVICE_STATE", 100), 7 * kSec).accepted);
  EXPECT_TRUE(t.expire(8 * kSec).empty());
}

// A client silent past the timeout is suspended, not forgotten: its stream keeps flowing (a
// pulled cable put back is served at once) until the grace ends.
TEST(Subscriptions, ASilentClientIsSuspendedThenForgottenAfterTheGrace) {
  srv::SubscriptionLimits l = limits();  // 2 s
  l.client_grace_ns = 3 * kSec;
  srv::SubscriptionTable t(l);
  ASSERT_TRUE(t.handleRequest(request("silent", "DEVICE_STATE", 100), 0).accepted);
  EXPECT_TRUE(t.expire(2 * kSec).empty());
  EXPECT_TRUE(t.takeChanges().empty());  // exactly the timeout is still alive
  EXPECT_TRUE(t.expire(2 * kSec + 1).empty());
  const auto changes = t.takeChanges();
  ASSERT_EQ(changes.size(), 1u);
  EXPECT_EQ(changes[0].client_id, "silent");
  EXPECT_FALSE(changes[0].back);
  EXPECT_EQ(changes[0].silent_ns, 2 * kSec + 1);
  EXPECT_EQ(t.counters().suspended_clients, 1u);
  EXPECT_TRUE(t.expire(4 * kSec).empty());
  EXPECT_TRUE(t.takeChanges().empty());  // suspended once, not at every check
  test::RecordingSink sink;
  runTicks(t, sink, 0, 100);
  EXPECT_EQ(sink.statesOn("THX_DEVICE_STATE.silent"), 10u);  // still served
  EXPECT_EQ(t.numClients(), 1);
  EXPECT_TRUE(t.expire(5 * kSec).empty());  // timeout + grace: still kept
  EXPECT_EQ(t.expire(5 * kSec + 1), std::vector<std::string>{"silent"});
  EXPECT_EQ(t.numClients(), 0);
  EXPECT_EQ(t.counters().expired_clients, 1u);
}

// Heard from again within the grace (a heartbeat here, or a request), the client is served as
// before: the same grant and the same batch sequence, nothing to ask again.
TEST(Subscriptions, ASuspendedClientHeardFromAgainIsServedAsBefore) {
  srv::SubscriptionTable t(limits());  // 2 s, and the default grace (10 s)
  ASSERT_TRUE(t.handleRequest(request("audio", "CONTACT", 100.0, true), 0).accepted);
  test::RecordingSink sink;
  runTicks(t, sink, 0, 1000);
  ASSERT_FALSE(sink.batches.empty());
  const std::int64_t last_seq = sink.batches.back().second.seq;
  EXPECT_TRUE(t.expire(3 * kSec).empty());
  ASSERT_EQ(t.takeChanges().size(), 1u);  // suspended
  runTicks(t, sink, 1000, 1000);          // the outage: batches go out, nobody hears them
  thx_msgs::heartbeat_t hb{};
  hb.client_id = "audio";
  EXPECT_TRUE(t.heartbeat(hb, 4 * kSec));
  const auto changes = t.takeChanges();
  ASSERT_EQ(changes.size(), 1u);
  EXPECT_TRUE(changes[0].back);
  EXPECT_EQ(changes[0].silent_ns, 4 * kSec);
  EXPECT_EQ(t.counters().resumed_clients, 1u);
  EXPECT_TRUE(t.expire(5 * kSec).empty());
  EXPECT_TRUE(t.takeChanges().empty());  // alive again: not suspended anew
  std::int64_t seq = 0;
  for (const auto& [channel, b] : sink.batches) {
    EXPECT_EQ(b.seq, seq + 1) << "one sequence through the outage";
    seq = b.seq;
  }
  EXPECT_GT(seq, last_seq);
}

// Forgotten and subscribed again, a batch channel goes on with its sequence: what arrives after
// the gap is new data to the client, not a repeat (docs/messages.md, contact_batch_t).
TEST(Subscriptions, ABatchSequenceGoesOnWhenAForgottenClientSubscribesAgain) {
  srv::SubscriptionLimits l = limits();
  l.client_grace_ns = 0;
  srv::SubscriptionTable t(l);
  ASSERT_TRUE(t.handleRequest(request("audio", "CONTACT", 100.0, true), 0).accepted);
  test::RecordingSink sink;
  runTicks(t, sink, 0, 500);
  ASSERT_FALSE(sink.batches.empty());
  // The next batch sent, from `first_tick` on, is the one after the last batch sent so far.
  auto expectTheSequenceGoesOn = [&](std::int64_t first_tick, const char* after) {
    SCOPED_TRACE(after);
    const std::int64_t last = sink.batches.back().second.seq;
    const std::size_t n = sink.batches.size();
    runTicks(t, sink, first_tick, 500);
    ASSERT_GT(sink.batches.size(), n);
    EXPECT_EQ(sink.batches[n].second.seq, last + 1);
  };
  ASSERT_EQ(t.expire(3 * kSec), std::vector<std::string>{"audio"});
  ASSERT_TRUE(t.handleRequest(request("audio", "CONTACT", 100.0, true, 2), 3 * kSec).accepted);
  expectTheSequenceGoesOn(3000, "forgotten, then subscribed again");
  Req unsub = request("audio", "CONTACT", 100.0, true, 3);
  unsub.action = Req::ACTION_UNSUBSCRIBE;
  ASSERT_TRUE(t.handleRequest(unsub, 3 * kSec).accepted);
  ASSERT_TRUE(t.handleRequest(request("audio", "CONTACT", 100.0, true, 4), 3 * kSec).accepted);
  expectTheSequenceGoesOn(3500, "unsubscribed, then subscribed again");
  ASSERT_TRUE(t.handleRequest(request("audio", "CONTACT", 50.0, true, 5), 3 * kSec).accepted);
  expectTheSequenceGoesOn(4000, "a new rate on the channel");
}

// Batching: every tick's sample reaches a 100 Hz client, in order, exactly once.
TEST(Subscriptions, BatchesCarryEveryTickExactlyOnce) {
  srv::SubscriptionTable t(limits());
  ASSERT_TRUE(t.handleRequest(request("audio", "CONTACT", 100.0, true), 0).accepted);
  ASSERT_TRUE(t.handleRequest(request("slow", "CONTACT", 7.0, true), 0).accepted);
  test::RecordingSink sink;
  runTicks(t, sink, 500, 3000);
  t.flushBatches(0, sink);
  for (const char* ch : {"THX_CONTACT_BATCH.audio", "THX_CONTACT_BATCH.slow"}) {
    std::int64_t expect_tick = 500, seq = 0;
    std::size_t largest = 0;
    for (const auto& [channel, b] : sink.batches) {
      if (channel != ch) continue;
      EXPECT_EQ(b.seq, ++seq);
      EXPECT_EQ(b.server_instance, 77);
      EXPECT_EQ(b.num_dropped, 0);
      ASSERT_TRUE(thx_msgs::batch_count_consistent(b));
      for (const auto& s : b.samples) EXPECT_EQ(s.tick, expect_tick++);
      EXPECT_EQ(b.next_tick, expect_tick);
      largest = std::max(largest, b.samples.size());
    }
    EXPECT_EQ(expect_tick, 3500) << ch;  // all 3000 samples
    EXPECT_LE(largest, thx_msgs::max_unfragmented_batch_samples(std::string(ch).size())) << ch;
    if (std::string(ch) == "THX_CONTACT_BATCH.audio") {
      EXPECT_EQ(seq, 300);  // 100 Hz for 3 s
    }
  }
  EXPECT_EQ(t.counters().batch_samples, 6000u);
}

TEST(Subscriptions, TicksLostBeforeThePublisherAreCountedAsDropped) {
  srv::SubscriptionTable t(limits());
  ASSERT_TRUE(t.handleRequest(request("audio", "CONTACT", 100.0, true), 0).accepted);
  test::RecordingSink sink;
  runTicks(t, sink, 0, 15);
  runTicks(t, sink, 20, 30);  // ticks 15..19 never reached the publisher (ring overflow)
  runTicks(t, sink, 48, 5);   // an older tick again: ignored
  t.flushBatches(0, sink);
  std::int64_t prev_next = 0, samples = 0, dropped = 0;
  for (const auto& [ch, b] : sink.batches) {
    EXPECT_EQ(b.next_tick - b.num_samples - b.num_dropped, prev_next);  // the documented continuity check
    prev_next = b.next_tick;
    samples += b.num_samples;
    dropped += b.num_dropped;
  }
  EXPECT_EQ(samples, 45 + 3);  // 0..14, 20..49, then 50..52 of the repeated run
  EXPECT_EQ(dropped, 5);
}

TEST(Subscriptions, AResendKeepsTheStreamAndAChangeReplacesIt) {
  srv::SubscriptionTable t(limits());
  ASSERT_TRUE(t.handleRequest(request("audio", "CONTACT", 100.0, true, 1), 0).accepted);
  test::RecordingSink sink;
  runTicks(t, sink, 0, 25);
  // The reply was lost, the client resends: same schedule, same batch sequence, no sample lost.
  ASSERT_TRUE(t.handleRequest(request("audio", "CONTACT", 100.0, true, 2), 0).accepted);
  runTicks(t, sink, 25, 25);
  ASSERT_EQ(sink.batches.size(), 4u);  // at ticks 10, 20, 30, 40
  EXPECT_EQ(sink.batches.back().second.seq, 4);
  EXPECT_EQ(sink.batches.back().second.next_tick, 41);
  // Asking CONTACT without batching replaces the batched stream.
  const auto r = t.handleRequest(request("audio", "CONTACT", 50.0, false, 3), 0);
  ASSERT_TRUE(r.accepted);
  EXPECT_EQ(r.channel, "THX_CONTACT.audio");
  EXPECT_EQ(t.numSubscriptions(), 1);
  sink = {};
  runTicks(t, sink, 50, 100);
  EXPECT_TRUE(sink.batches.empty());
  EXPECT_EQ(sink.contacts.size(), 5u);
}

TEST(Subscriptions, ServoStatsFollowTheirOwnRateAndCountClients) {
  srv::SubscriptionTable t(limits());
  ASSERT_TRUE(t.handleRequest(request("mon", "SERVO_STATS", 0.5), 0).accepted);
  ASSERT_TRUE(t.handleRequest(request("vis", "DEVICE_STATE", 30), 0).accepted);
  EXPECT_TRUE(t.wantsTicks());
  test::RecordingSink sink;
  for (int w = 0; w < 10; ++w) t.onStats(thx_msgs::servo_stats_t{}, sink);
  ASSERT_EQ(sink.stats.size(), 5u);  // every second window
  EXPECT_EQ(sink.stats[0].first, "THX_SERVO_STATS.mon");
  EXPECT_EQ(sink.stats[0].second.num_clients, 2);
  EXPECT_EQ(sink.stats[0].second.num_subscriptions, 2);
}

TEST(Subscriptions, NothingIsComputedWithoutSubscribers) {
  srv::SubscriptionTable t(limits());
  EXPECT_FALSE(t.wantsTicks());
  ASSERT_TRUE(t.handleRequest(request("mon", "SERVO_STATS", 1), 0).accepted);
  EXPECT_FALSE(t.wantsTicks());  // stats need no per-tick messages
}

}  // namespace test_subscriptions
