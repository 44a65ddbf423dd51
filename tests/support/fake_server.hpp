#pragma once
// An in-process fake hapticd for client tests: the server side of the protocol as hapticd's
// publisher does it (server/subscriptions.hpp: the real subscription table), minus threads and
// the servo. It answers subscription requests and heartbeats, sends hello on hello(), and
// publishes every subscriber's streams from ticks the test makes up (ticks(), flush()), on any
// LCM provider (memq:// keeps everything in the test's process). Time is the test's: a clock
// variable it advances. Nothing happens outside the test's own calls to lcm.handle()/poll.
// Links thx_server_io.
#include <gtest/gtest.h>

#include <cstdint>
#include <lcm/lcm-cpp.hpp>
#include <string>
#include <thx_msgs/protocol.hpp>

#include "server/subscriptions.hpp"

namespace thx::test {

class FakeServer : public srv::MessageSink {
 public:
  // `now` is the test's clock (ns), read whenever a request or heartbeat arrives; `instance` the
  // server instance its hello and replies carry (a new one looks like a restarted hapticd).
  FakeServer(lcm::LCM& lcm, std::int64_t instance, const std::int64_t& now, int max_clients = 8)
      : lcm_(lcm), now_(now), table_([&] {
          srv::SubscriptionLimits l;
          l.server_instance = instance;
          l.max_clients = max_clients;
          return l;
        }()),
        instance_(instance) {
    req_sub_ = lcm_.subscribe(thx_msgs::kChannelSubscribe, &FakeServer::onRequest, this);
    hb_sub_ = lcm_.subscribe(thx_msgs::kChannelHeartbeat, &FakeServer::onHeartbeat, this);
  }
  ~FakeServer() override {
    lcm_.unsubscribe(req_sub_);
    lcm_.unsubscribe(hb_sub_);
  }
  void onRequest(const lcm::ReceiveBuffer* rbuf, const std::string&) {
    thx_msgs::subscribe_request_t r;
    ASSERT_GT(thx_msgs::try_decode(rbuf->data, rbuf->data_size, r), 0);
    ++requests;
    if (mute) return;
    thx_msgs::subscribe_reply_t reply = table_.handleRequest(r, now_);
    lcm_.publish(thx_msgs::kChannelSubscribeReply, &reply);
  }
  void onHeartbeat(const lcm::ReceiveBuffer* rbuf, const std::string&) {
    thx_msgs::heartbeat_t h;
    ASSERT_GT(thx_msgs::try_decode(rbuf->data, rbuf->data_size, h), 0);
    ++heartbeats;
    last_heartbeat_instance = h.server_instance;
    table_.heartbeat(h, now_);
  }
  // One THX_HELLO, as hapticd sends every second.
  void hello() {
    thx_msgs::hello_t h{};
    h.seq = ++hello_seq_;
    h.server_instance = instance_;
    h.protocol_version = thx_msgs::hello_t::PROTOCOL_VERSION;
    h.servo_rate_hz = 1000;
    h.server_name = "fake";
    h.device = "sim";
    lcm_.publish(thx_msgs::kChannelHello, &h);
  }
  // Servo ticks first .. first+n-1 (1 ms apart), through the subscription table to every subscriber.
  void ticks(std::int64_t first, std::int64_t n) {
    thx_msgs::device_state_t d{};
    thx_msgs::contact_t c{};
    for (std::int64_t k = first; k < first + n; ++k) {
      d.tick = c.tick = k;
      table_.onTick(d, c, k * 1000, *this);
    }
  }
  // Sends the partly filled batches now.
  void flush() { table_.flushBatches(0, *this); }
  srv::SubscriptionTable& table() { return table_; }

  void send(const std::string& ch, const thx_msgs::device_state_t& m) override { lcm_.publish(ch, &m); }
  void send(const std::string& ch, const thx_msgs::contact_t& m) override { lcm_.publish(ch, &m); }
  void send(const std::string& ch, const thx_msgs::contact_batch_t& m) override { lcm_.publish(ch, &m); }
  void send(const std::string& ch, const thx_msgs::servo_stats_t& m) override { lcm_.publish(ch, &m); }

  int requests = 0, heartbeats = 0;
  std::int64_t last_heartbeat_instance = -1;
  bool mute = false;  // receive but do not answer

 private:
  lcm::LCM& lcm_;
  const std::int64_t& now_;
  srv::SubscriptionTable table_;
  std::int64_t instance_;
  std::int64_t hello_seq_ = 0;
  lcm::Subscription* req_sub_ = nullptr;
  lcm::Subscription* hb_sub_ = nullptr;
};

}  // namespace thx::test
