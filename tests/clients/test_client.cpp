// The client library (clients/client_lib) against the fake hapticd of tests/support (the real
// subscription table), all in one process over memq:// with a fake clock: subscribe, resend, heartbeats,
// restart and silence detection, refusals, batches, garbage. Deterministic: no network, no sleeps.
#include <gtest/gtest.h>

#include <lcm/lcm-cpp.hpp>
#include <memory>
#include <thx_msgs/protocol.hpp>

#include "base/error.hpp"
#include "tests/support/fake_server.hpp"
#include "thx_client/client.hpp"

namespace test_client {

using namespace thx;
using client::Client;
using client::SubscriptionState;
using test::FakeServer;

namespace {

constexpr std::int64_t kMs = 1'000'000;

class ClientTest : public ::testing::Test {
 protected:
  void SetUp() override { ASSERT_TRUE(lcm_.good()); }
  std::unique_ptr<Client> makeClient(const std::string& id = "probe") {
    client::ClientOptions o;
    o.client_id = id;
    o.clock = [this] { return now_; };
    return std::make_unique<Client>(lcm_, o);
  }
  // Lets the messages in flight settle (each poll handles what the previous one published).
  void pump(Client& c) {
    for (int k = 0; k < 4; ++k) c.poll(0);
  }
  // Advances the fake clock in steps, polling at each.
  void advance(Client& c, std::int64_t ns, std::int64_t step = 10 * kMs) {
    for (std::int64_t t = 0; t < ns; t += step) {
      now_ += step;
      pump(c);
    }
  }

  lcm::LCM lcm_{"memq://"};
  std::int64_t now_ = 1'000 * kMs;
};

}  // namespace

TEST_F(ClientTest, SubscribesAndReceivesAtItsRateWithLatestValues) {
  FakeServer server(lcm_, 11, now_);
  auto c = makeClient();
  int calls = 0;
  c->onDeviceState([&](const thx_msgs::device_state_t&, std::int64_t t) {
    ++calls;
    EXPECT_EQ(t, now_);  // receipt time on the client's clock
  });
  EXPECT_FALSE(c->latestDeviceState());
  c->subscribe(thx_msgs::Stream::DeviceState, 100.0);
  pump(*c);
  ASSERT_TRUE(c->allActive());
  const auto st = c->status(thx_msgs::Stream::DeviceState);
  EXPECT_EQ(st->channel, "THX_DEVICE_STATE.probe");
  EXPECT_DOUBLE_EQ(st->granted_hz, 100.0);
  EXPECT_EQ(c->serverInstance(), 11);
  server.ticks(0, 100);
  pump(*c);
  EXPECT_EQ(calls, 10);
  EXPECT_EQ(c->status(thx_msgs::Stream::DeviceState)->messages, 10u);
  ASSERT_TRUE(c->latestDeviceState());
  EXPECT_EQ(c->latestDeviceState()->tick, 90);
  EXPECT_EQ(server.requests, 1);
}

TEST_F(ClientTest, ResendsUnansweredRequestsWithBackoff) {
  FakeServer server(lcm_, 11, now_);
  server.mute = true;
  auto c = makeClient();
  c->subscribe(thx_msgs::Stream::Contact, 50.0);
  pump(*c);
  EXPECT_EQ(server.requests, 1);
  advance(*c, 150 * kMs);
  EXPECT_EQ(server.requests, 1);
  advance(*c, 100 * kMs);  // 250 ms: resent after 200 ms
  EXPECT_EQ(server.requests, 2);
  advance(*c, 10'000 * kMs);  // then 400, 800, 1600, 2000, 2000, ... ms apart: at 0.6, 1.4, 3, 5, 7, 9 s
  EXPECT_EQ(server.requests, 8);
  server.mute = false;
  advance(*c, 2'100 * kMs);
  EXPECT_TRUE(c->allActive());
}

TEST_F(ClientTest, HeartbeatsKeepTheClientAliveAtTheServer) {
  FakeServer server(lcm_, 11, now_);  // 2 s timeout: a heartbeat every 0.5 s
  auto c = makeClient();
  c->subscribe(thx_msgs::Stream::DeviceState, 10.0);
  pump(*c);
  ASSERT_TRUE(c->allActive());
  const int before = server.heartbeats;
  for (int k = 0; k < 10; ++k) {
    advance(*c, 500 * kMs);
    server.hello();  // the server is alive too
    EXPECT_TRUE(server.table().expire(now_).empty()) << k;
  }
  EXPECT_GE(server.heartbeats - before, 9);
  EXPECT_LE(server.heartbeats - before, 11);
  EXPECT_EQ(server.last_heartbeat_instance, 11);
  EXPECT_EQ(server.table().numClients(), 1);
}

TEST_F(ClientTest, ANewServerInstanceMakesTheClientSubscribeAgain) {
  auto server = std::make_unique<FakeServer>(lcm_, 11, now_);
  auto c = makeClient();
  c->subscribe(thx_msgs::Stream::Contact, 100.0, true);
  pump(*c);
  ASSERT_TRUE(c->allActive());
  server.reset();  // hapticd restarts: a new instance with an empty table
  server = std::make_unique<FakeServer>(lcm_, 22, now_);
  server->hello();
  pump(*c);
  EXPECT_EQ(c->serverInstance(), 22);
  EXPECT_EQ(c->counters().reconnects, 1u);
  EXPECT_TRUE(c->allActive());
  EXPECT_EQ(server->table().numSubscriptions(), 1);
  std::int64_t samples = 0;
  c->onContactBatch([&](const thx_msgs::contact_batch_t& b, std::int64_t) { samples += b.num_samples; });
  server->ticks(0, 100);
  pump(*c);
  EXPECT_EQ(samples, 91);  // batches at ticks 10, 20, ..., 90
}

TEST_F(ClientTest, ASilentServerIsAskedAgain) {
  FakeServer server(lcm_, 11, now_);
  auto c = makeClient();
  c->subscribe(thx_msgs::Stream::DeviceState, 10.0);
  pump(*c);
  ASSERT_TRUE(c->allActive());
  const int before = server.requests;
  advance(*c, 2'900 * kMs, 100 * kMs);  // nothing from the server, below the 3 s silence
  EXPECT_EQ(server.requests, before);
  advance(*c, 300 * kMs, 100 * kMs);
  EXPECT_EQ(c->counters().reconnects, 1u);
  EXPECT_EQ(server.requests, before + 1);
  EXPECT_TRUE(c->allActive());  // the live server kept the subscription and answered
  EXPECT_EQ(server.table().numSubscriptions(), 1);
}

// The client was paused past the server's heartbeat timeout: the server forgot it, but its
// hellos keep coming. The silence of the stream itself brings the subscription back.
TEST_F(ClientTest, AForgottenClientSubscribesAgain) {
  FakeServer server(lcm_, 11, now_);
  auto c = makeClient();
  c->subscribe(thx_msgs::Stream::DeviceState, 100.0);
  pump(*c);
  server.ticks(0, 100);
  pump(*c);
  ASSERT_EQ(c->status(thx_msgs::Stream::DeviceState)->messages, 10u);
  now_ += 2'500 * kMs;  // paused: no poll, no heartbeat
  ASSERT_EQ(server.table().expire(now_).size(), 1u);
  std::int64_t tick = 100;
  for (int k = 0; k < 40; ++k) {  // 4 s of hellos and ticks
    server.hello();
    server.ticks(tick, 100);
    tick += 100;
    advance(*c, 100 * kMs, 100 * kMs);
  }
  EXPECT_EQ(c->counters().reconnects, 1u);
  EXPECT_EQ(server.table().numClients(), 1);
  EXPECT_GT(c->status(thx_msgs::Stream::DeviceState)->messages, 10u);
}

TEST_F(ClientTest, ARefusalIsReportedAndNotRetried) {
  FakeServer full(lcm_, 11, now_, /*max_clients=*/0);
  auto c = makeClient();
  std::string reason;
  c->onStatus([&](const client::StreamStatus& s) { reason = s.reason; });
  c->subscribe(thx_msgs::Stream::DeviceState, 10.0);
  pump(*c);
  const auto st = c->status(thx_msgs::Stream::DeviceState);
  EXPECT_EQ(st->state, SubscriptionState::Refused);
  EXPECT_NE(st->reason.find("too many clients"), std::string::npos) << st->reason;
  EXPECT_EQ(reason, st->reason);
  EXPECT_FALSE(c->allActive());
  advance(*c, 2'000 * kMs, 100 * kMs);
  EXPECT_EQ(full.requests, 1);
}

TEST_F(ClientTest, OnlyItsOwnRepliesCount) {
  FakeServer server(lcm_, 11, now_);
  auto a = makeClient("a");
  auto b = makeClient("b");
  a->subscribe(thx_msgs::Stream::DeviceState, 10.0);
  b->subscribe(thx_msgs::Stream::DeviceState, 500.0);
  pump(*a);
  pump(*b);
  pump(*a);
  EXPECT_DOUBLE_EQ(a->status(thx_msgs::Stream::DeviceState)->granted_hz, 10.0);
  EXPECT_DOUBLE_EQ(b->status(thx_msgs::Stream::DeviceState)->granted_hz, 500.0);
  server.ticks(0, 100);
  pump(*a);
  EXPECT_EQ(a->status(thx_msgs::Stream::DeviceState)->messages, 1u);  // 10 Hz: one per 100 ticks
  EXPECT_EQ(b->status(thx_msgs::Stream::DeviceState)->messages, 50u);
  b.reset();  // unsubscribes politely
  pump(*a);
  EXPECT_EQ(server.table().numClients(), 1);
}

TEST_F(ClientTest, BatchesDeliverEveryTickAndTheLatestSample) {
  FakeServer server(lcm_, 11, now_);
  auto c = makeClient();
  std::int64_t next = 0;
  bool ordered = true;
  c->onContactBatch([&](const thx_msgs::contact_batch_t& b, std::int64_t) {
    for (const auto& s : b.samples) ordered = ordered && s.tick == next++;
  });
  c->subscribe(thx_msgs::Stream::Contact, 100.0, true);
  pump(*c);
  for (int k = 0; k < 10; ++k) {
    server.ticks(k * 100, 100);
    pump(*c);
  }
  server.flush();
  pump(*c);
  EXPECT_TRUE(ordered);
  EXPECT_EQ(next, 1000);
  ASSERT_TRUE(c->latestContact());
  EXPECT_EQ(c->latestContact()->tick, 999);
}

TEST_F(ClientTest, GarbageOnItsChannelsIsCountedAndHarmless) {
  FakeServer server(lcm_, 11, now_);
  auto c = makeClient();
  c->subscribe(thx_msgs::Stream::DeviceState, 100.0);
  pump(*c);
  ASSERT_TRUE(c->allActive());
  const std::string junk = "\xff\xff\xff\xff not an LCM message";
  for (const char* ch : {thx_msgs::kChannelHello, thx_msgs::kChannelSubscribeReply, "THX_DEVICE_STATE.probe"}) {
    lcm_.publish(ch, junk.data(), unsigned(junk.size()));
  }
  pump(*c);
  EXPECT_EQ(c->counters().undecodable, 3u);
  server.ticks(0, 20);
  pump(*c);
  EXPECT_EQ(c->status(thx_msgs::Stream::DeviceState)->messages, 2u);
}

TEST_F(ClientTest, BadArgumentsAreClearErrors) {
  client::ClientOptions o;
  o.client_id = "has space";
  try {
    Client c(lcm_, o);
    FAIL() << "accepted an invalid client id";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), Error::Kind::Config);
    EXPECT_NE(std::string(e.what()).find("client_id 'has space'"), std::string::npos) << e.what();
  }
  auto c = makeClient();
  auto messageOf = [](const std::function<void()>& f) -> std::string {
    try {
      f();
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), Error::Kind::Config) << e.what();
      return e.what();
    }
    return "(no thx::Error)";
  };
  EXPECT_EQ(messageOf([&] { c->subscribe(thx_msgs::Stream::DeviceState, 10.0, true); }),
            "stream DEVICE_STATE: only CONTACT can be batched");
  EXPECT_EQ(messageOf([&] { c->subscribe(thx_msgs::Stream::ServoStats, 0.0); }),
            "stream SERVO_STATS: rate 0.000000 Hz: expected a finite number > 0");
  // A stream is a thx_msgs::Stream: only a cast makes another value, a bug in the caller.
  EXPECT_THROW(c->subscribe(static_cast<thx_msgs::Stream>(7), 10.0), std::logic_error);
  EXPECT_TRUE(c->status().empty());  // nothing was asked for
}

}  // namespace test_client
