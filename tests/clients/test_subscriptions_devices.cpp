// hapticd's subscription table serving several devices (issue 30, protocol 6): one grant per
// stream and client, scheduled per device, so each device's messages arrive at the granted rate
// tagged with their device index. Driven by hand like tests/clients/test_subscriptions.cpp: tick
// numbers for rates, a recording sink instead of LCM.
#include <gtest/gtest.h>

#include <cstdio>
#include <initializer_list>
#include <thx_msgs/protocol.hpp>

#include "base/error.hpp"
#include "recording_sink.hpp"
#include "server/subscriptions.hpp"

namespace test_subscriptions_devices {

using namespace thx;
using test::request;
using State = thx_msgs::device_state_t;

namespace {

srv::SubscriptionLimits limits(int devices) {
  srv::SubscriptionLimits l;
  l.servo_rate_hz = 1000.0;
  l.max_rate_hz = 1000.0;
  l.max_bandwidth_bytes_per_s = 8e6;
  l.server_instance = 77;
  l.devices = devices;
  return l;
}

// Also keeps every contact whole (RecordingSink keeps its channel and tick only).
struct Sink : test::RecordingSink {
  using RecordingSink::send;
  std::vector<thx_msgs::contact_t> contact_msgs;
  void send(const std::string& ch, const thx_msgs::contact_t& m) override {
    RecordingSink::send(ch, m);
    contact_msgs.push_back(m);
  }
};

// Tick `k` of `device`, as the publisher hands it over: state and contact tagged alike.
void tick(srv::SubscriptionTable& t, srv::MessageSink& sink, int device, std::int64_t k, std::int32_t flags = 0,
          std::int32_t faults = 0) {
  State d{};
  thx_msgs::contact_t c{};
  d.tick = c.tick = k;
  d.utime = c.utime = k * 1000;
  d.device = c.device = device;
  d.flags = d.flags_seen = flags;
  d.fault_mask = faults;
  t.onTick(d, c, k * 1000, sink);
}

// Ticks [first, first + n) of every device in `devices`, device by device within a tick.
void run(srv::SubscriptionTable& t, srv::MessageSink& sink, std::initializer_list<int> devices, std::int64_t first,
         std::int64_t n) {
  for (std::int64_t k = first; k < first + n; ++k) {
    for (int d : devices) tick(t, sink, d, k);
  }
}

thx_msgs::servo_stats_t statsOf(int device) {
  thx_msgs::servo_stats_t s{};
  s.device = device;
  return s;
}

// Each device's flag of its own in DEVICE_STATE's test.
std::int32_t ownFlag(int device) { return device == 2 ? State::FLAG_IN_CONTACT : std::int32_t(State::FLAG_ENGAGED); }

std::string kB(double bytes_per_s) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", bytes_per_s / 1e3);
  return buf;
}

}  // namespace

// 100 Hz of a 1 kHz servo is 100 Hz of each device, and a fault on device 1 reaches device 1's
// next message only: flags_seen and fault_mask are OR-ed over each device's own ticks.
TEST(SubscriptionsDevices, DeviceStateAtItsRateOfEachDeviceWithItsOwnFlags) {
  srv::SubscriptionTable t(limits(3));
  ASSERT_TRUE(t.handleRequest(request("vis", "DEVICE_STATE", 100.0), 0).accepted);
  Sink sink;
  const std::int32_t fault_bits = 1 << State::FAULT_FORCE_BUDGET;
  for (std::int64_t k = 0; k < 1000; ++k) {
    for (int d = 0; d < 3; ++d) {
      // Every device has a flag of its own on every tick; device 1 alone a fault on tick 15.
      const bool fault = d == 1 && k == 15;
      const std::int32_t flags = ownFlag(d) | (fault ? State::FLAG_FAULT : 0);
      tick(t, sink, d, k, flags, fault ? fault_bits : 0);
    }
  }
  ASSERT_EQ(sink.state_msgs.size(), 300u);
  std::int64_t expect_tick[3] = {0, 0, 0};
  for (std::size_t i = 0; i < sink.states.size(); ++i) {
    const State& m = sink.state_msgs[i];
    ASSERT_GE(m.device, 0);
    ASSERT_LT(m.device, 3);
    EXPECT_EQ(sink.states[i].channel, "THX_DEVICE_STATE.vis");
    EXPECT_EQ(m.tick, expect_tick[m.device]) << "device " << m.device;
    expect_tick[m.device] += 10;
    // The message at tick 20 covers ticks 11..20 of its device, tick 15's fault among them.
    const bool covers_fault = m.device == 1 && m.tick == 20;
    EXPECT_EQ(m.fault_mask, covers_fault ? fault_bits : 0) << "device " << m.device << " tick " << m.tick;
    EXPECT_EQ(m.flags_seen, ownFlag(m.device) | (covers_fault ? State::FLAG_FAULT : 0)) << "device " << m.device << " tick " << m.tick;
  }
  for (int d = 0; d < 3; ++d) EXPECT_EQ(expect_tick[d], 1000) << "100 messages of device " << d;
}

TEST(SubscriptionsDevices, ContactAtItsRateOfEachDevice) {
  srv::SubscriptionTable t(limits(2));
  ASSERT_TRUE(t.handleRequest(request("phys", "CONTACT", 50.0), 0).accepted);
  Sink sink;
  run(t, sink, {0, 1}, 0, 1000);
  ASSERT_EQ(sink.contact_msgs.size(), 100u);
  std::int64_t expect_tick[2] = {0, 0};
  for (const auto& c : sink.contact_msgs) {
    ASSERT_TRUE(c.device == 0 || c.device == 1) << c.device;
    EXPECT_EQ(c.tick, expect_tick[c.device]);
    expect_tick[c.device] += 20;
  }
  EXPECT_EQ(expect_tick[0], 1000);
  EXPECT_EQ(expect_tick[1], 1000);
}

// One batch per device on the one channel, each with its device, its own sequence 1, 2, 3...
// and its own count of dropped ticks.
TEST(SubscriptionsDevices, ContactBatchesAreKeptPerDevice) {
  srv::SubscriptionTable t(limits(2));
  ASSERT_TRUE(t.handleRequest(request("audio", "CONTACT", 100.0, true), 0).accepted);
  Sink sink;
  for (std::int64_t k = 0; k < 300; ++k) {
    tick(t, sink, 0, k);
    if (k < 100 || k >= 105) tick(t, sink, 1, k);  // device 1's ticks 100..104 never arrive
  }
  t.flushBatches(0, sink);
  for (int d = 0; d < 2; ++d) {
    SCOPED_TRACE("device " + std::to_string(d));
    std::int64_t seq = 0, prev_next = 0, samples = 0, dropped = 0;
    for (const auto& [channel, b] : sink.batches) {
      if (b.device != d) continue;
      EXPECT_EQ(channel, "THX_CONTACT_BATCH.audio");
      EXPECT_EQ(b.seq, ++seq);
      EXPECT_EQ(b.server_instance, 77);
      ASSERT_TRUE(thx_msgs::batch_count_consistent(b));
      EXPECT_EQ(b.next_tick - b.num_samples - b.num_dropped, prev_next);  // the documented continuity check
      for (const auto& s : b.samples) EXPECT_EQ(s.device, d);
      prev_next = b.next_tick;
      samples += b.num_samples;
      dropped += b.num_dropped;
    }
    EXPECT_EQ(seq, 30);  // 100 Hz for 0.3 s
    EXPECT_EQ(prev_next, 300);
    EXPECT_EQ(samples, d == 0 ? 300 : 295);
    EXPECT_EQ(dropped, d == 0 ? 0 : 5);
  }
  EXPECT_EQ(sink.batches.size(), 60u);
  EXPECT_EQ(t.counters().batch_samples, 595u);
}

// Subscribed again, the channel goes on with each device's own sequence.
TEST(SubscriptionsDevices, EachDevicesBatchSequenceGoesOnWhenSubscribedAgain) {
  srv::SubscriptionTable t(limits(2));
  ASSERT_TRUE(t.handleRequest(request("audio", "CONTACT", 100.0, true), 0).accepted);
  Sink sink;
  run(t, sink, {0}, 0, 505);  // device 0: 50 batches
  run(t, sink, {1}, 0, 205);  // device 1: 20 batches
  auto unsub = request("audio", "CONTACT", 100.0, true, 2);
  unsub.action = thx_msgs::subscribe_request_t::ACTION_UNSUBSCRIBE;
  ASSERT_TRUE(t.handleRequest(unsub, 0).accepted);
  ASSERT_EQ(t.numClients(), 0);
  ASSERT_TRUE(t.handleRequest(request("audio", "CONTACT", 100.0, true, 3), 0).accepted);
  sink = {};
  run(t, sink, {0, 1}, 1000, 100);
  std::int64_t first_seq[2] = {0, 0};
  for (const auto& [channel, b] : sink.batches) {
    if (first_seq[b.device] == 0) first_seq[b.device] = b.seq;
  }
  EXPECT_EQ(first_seq[0], 51);
  EXPECT_EQ(first_seq[1], 21);
}

// SERVO_STATS: each device's windows are counted apart, so 0.5 Hz is every second window of
// each device.
TEST(SubscriptionsDevices, ServoStatsAtTheirRateOfEachDevice) {
  srv::SubscriptionTable t(limits(2));
  ASSERT_TRUE(t.handleRequest(request("mon", "SERVO_STATS", 0.5), 0).accepted);
  ASSERT_TRUE(t.handleRequest(request("all", "SERVO_STATS", 1.0), 0).accepted);
  Sink sink;
  for (int w = 0; w < 10; ++w) {
    t.onStats(statsOf(0), sink);
    t.onStats(statsOf(1), sink);
  }
  int mon[2] = {0, 0}, all[2] = {0, 0};
  for (const auto& [channel, s] : sink.stats) {
    ASSERT_TRUE(s.device == 0 || s.device == 1) << s.device;
    EXPECT_EQ(s.num_clients, 2);
    EXPECT_EQ(s.num_subscriptions, 2);
    if (channel == "THX_SERVO_STATS.mon") ++mon[s.device];
    if (channel == "THX_SERVO_STATS.all") ++all[s.device];
  }
  EXPECT_EQ(mon[0], 5);
  EXPECT_EQ(mon[1], 5);
  EXPECT_EQ(all[0], 10);
  EXPECT_EQ(all[1], 10);
  EXPECT_EQ(sink.stats.size(), 30u);
}

TEST(SubscriptionsDevices, AnIndexNotServedIsCountedAndNotSent) {
  srv::SubscriptionTable t(limits(2));
  ASSERT_TRUE(t.handleRequest(request("vis", "DEVICE_STATE", 1000.0), 0).accepted);
  ASSERT_TRUE(t.handleRequest(request("vis", "CONTACT", 1000.0, true), 0).accepted);
  ASSERT_TRUE(t.handleRequest(request("vis", "SERVO_STATS", 1.0), 0).accepted);
  Sink sink;
  tick(t, sink, 2, 0);
  tick(t, sink, -1, 0);
  t.onStats(statsOf(16), sink);
  t.flushBatches(0, sink);
  EXPECT_TRUE(sink.states.empty());
  EXPECT_TRUE(sink.batches.empty());
  EXPECT_TRUE(sink.stats.empty());
  EXPECT_EQ(t.counters().foreign_device, 3u);
  EXPECT_EQ(t.counters().batch_samples, 0u);
  // The served devices are unaffected.
  tick(t, sink, 1, 0);
  t.onStats(statsOf(1), sink);
  ASSERT_EQ(sink.state_msgs.size(), 1u);
  EXPECT_EQ(sink.state_msgs[0].device, 1);
  ASSERT_EQ(sink.stats.size(), 1u);
  EXPECT_EQ(sink.stats[0].second.device, 1);
  EXPECT_EQ(t.counters().foreign_device, 3u);
}

// Every device's messages go out on the channel, so the bandwidth limit weighs them all.
TEST(SubscriptionsDevices, TheBandwidthLimitCountsEveryDevice) {
  const std::string channel = "THX_DEVICE_STATE.vis";
  const double one = srv::streamBandwidth(srv::StreamKind::DeviceState, 1000.0, 1000.0, channel.size());
  for (int devices : {1, 2, 4, 16}) {
    SCOPED_TRACE("devices " + std::to_string(devices));
    srv::SubscriptionLimits l = limits(devices);
    l.max_bandwidth_bytes_per_s = 4 * one;
    srv::SubscriptionTable t(l);
    const auto r = t.handleRequest(request("vis", "DEVICE_STATE", 1000.0), 0);
    if (devices <= 4) {
      EXPECT_TRUE(r.accepted) << r.reason;
      EXPECT_DOUBLE_EQ(t.bandwidth(), devices * one);
    } else {
      EXPECT_FALSE(r.accepted);
      EXPECT_NE(r.reason.find("bandwidth limit: this subscription needs " + kB(16 * one) + " kB/s"), std::string::npos)
          << r.reason;
      EXPECT_EQ(t.bandwidth(), 0.0);
      EXPECT_EQ(t.counters().refused, 1u);
    }
  }
}

TEST(SubscriptionsDevices, ADeviceCountOutsideOneToSixteenIsRefused) {
  for (int devices : {0, 17, -3}) {
    try {
      srv::SubscriptionTable t(limits(devices));
      ADD_FAILURE() << "devices = " << devices << " was accepted";
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), Error::Kind::Config);
      EXPECT_NE(std::string(e.what()).find("devices = " + std::to_string(devices)), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("expected 1 to 16"), std::string::npos) << e.what();
    }
  }
  EXPECT_EQ(srv::SubscriptionTable(limits(1)).limits().devices, 1);
  EXPECT_EQ(srv::SubscriptionTable(limits(16)).limits().devices, 16);
}

}  // namespace test_subscriptions_devices
