#pragma once
// An in-process fake hapticd for client tests: the server side of the protocol as hapticd's
// publisher does it (server/subscriptions.hpp: the real subscription table), minus threads and
// the servo. It answers subscription requests and heartbeats, sends hello on hello(), and
// publishes every subscriber's streams from ticks the test makes up (ticks(), flush()), on any
// LCM provider (memq:// keeps everything in the test's process). Time is the test's: a clock
// variable it advances. Nothing happens outside the test's own calls to lcm.handle()/poll.
// Its hello names a scene (scene_name, texture_fingerprint; switchScene() changes it and says so
// at once, as hapticd does after a load), and it answers server_command_t on THX_COMMAND as the
// test says (command_answer): accepted with command_tick, refused with `refusal`, or not at all;
// an accepted ACTION_LOAD_SCENE of a name in `scenes` switches to it, of another name is refused
// like hapticd's loader refuses a missing file.
// Links thx_server_io.
#include <gtest/gtest.h>

#include <cstdint>
#include <lcm/lcm-cpp.hpp>
#include <map>
#include <string>
#include <vector>
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
          l.client_grace_ns = 0;  // forgets a silent client at the timeout (hapticd --client-grace 0)
          return l;
        }()),
        instance_(instance) {
    req_sub_ = lcm_.subscribe(thx_msgs::kChannelSubscribe, &FakeServer::onRequest, this);
    hb_sub_ = lcm_.subscribe(thx_msgs::kChannelHeartbeat, &FakeServer::onHeartbeat, this);
    cmd_sub_ = lcm_.subscribe(thx_msgs::kChannelCommand, &FakeServer::onCommand, this);
  }
  ~FakeServer() override {
    lcm_.unsubscribe(req_sub_);
    lcm_.unsubscribe(hb_sub_);
    lcm_.unsubscribe(cmd_sub_);
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
  enum class CommandAnswer { Accept, Refuse, Ignore };
  void onCommand(const lcm::ReceiveBuffer* rbuf, const std::string&) {
    thx_msgs::server_command_t c;
    ASSERT_GT(thx_msgs::try_decode(rbuf->data, rbuf->data_size, c), 0);
    commands.push_back(c);
    if (command_answer == CommandAnswer::Ignore) return;
    thx_msgs::server_command_reply_t r{};
    r.server_instance = instance_;
    r.request_seq = c.seq;
    r.client_id = c.client_id;
    r.action = c.action;
    r.accepted = command_answer == CommandAnswer::Accept;
    r.reason = r.accepted ? "" : refusal;
    const bool load = c.action == thx_msgs::server_command_t::ACTION_LOAD_SCENE;
    if (r.accepted && load && !scenes.count(c.argument)) {
      r.accepted = false;  // as hapticd's loader: no such file in its scenes folder
      r.reason = "scene '" + c.argument + "' not found: no file scenes/" + c.argument + ".yaml";
    }
    r.tick = r.accepted ? command_tick : -1;
    lcm_.publish(thx_msgs::kChannelCommandReply, &r);
    if (r.accepted && load) switchScene(c.argument, scenes.at(c.argument));
  }
  // Runs another scene now and announces it with a hello at once, as hapticd after a load.
  void switchScene(const std::string& name, std::uint64_t fingerprint) {
    scene_name = name;
    texture_fingerprint = fingerprint;
    hello();
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
    h.scene_name = scene_name;
    h.texture_fingerprint = static_cast<std::int64_t>(texture_fingerprint);
    lcm_.publish(thx_msgs::kChannelHello, &h);
  }
  // Servo ticks first .. first+n-1 (1 ms apart), through the subscription table to every subscriber.
  void ticks(std::int64_t first, std::int64_t n) {
    thx_msgs::device_state_t d{};
    for (int k = 0; k < 3; ++k) d.p_world[k] = pen_world[k];
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
  // Where ticks() puts the pen (device_state_t.p_world), m.
  double pen_world[3] = {0, 0, 0};
  // The scene hello() announces.
  std::string scene_name = "default";
  std::uint64_t texture_fingerprint = 0x1111;
  // Commands: every one received, and how to answer.
  std::vector<thx_msgs::server_command_t> commands;
  CommandAnswer command_answer = CommandAnswer::Accept;
  std::string refusal = "refused by the fake server";
  std::int64_t command_tick = 1234;                // an accepted reply's tick
  std::map<std::string, std::uint64_t> scenes;    // what ACTION_LOAD_SCENE can load: name -> fingerprint

 private:
  lcm::LCM& lcm_;
  const std::int64_t& now_;
  srv::SubscriptionTable table_;
  std::int64_t instance_;
  std::int64_t hello_seq_ = 0;
  lcm::Subscription* req_sub_ = nullptr;
  lcm::Subscription* hb_sub_ = nullptr;
  lcm::Subscription* cmd_sub_ = nullptr;
};

}  // namespace thx::test
