#pragma once
// A MessageSink that keeps what the subscription table sends, for deterministic tests.
#include <string>
#include <vector>

#include "server/subscriptions.hpp"

namespace thx::test {

struct RecordingSink : srv::MessageSink {
  struct Sent {
    std::string channel;
    std::int64_t tick = -1;  // device state / contact
  };
  std::vector<Sent> states, contacts;
  std::vector<thx_msgs::device_state_t> state_msgs;  // every device state sent, whole
  std::vector<std::pair<std::string, thx_msgs::contact_batch_t>> batches;
  std::vector<std::pair<std::string, thx_msgs::servo_stats_t>> stats;

  void send(const std::string& ch, const thx_msgs::device_state_t& m) override {
    states.push_back({ch, m.tick});
    state_msgs.push_back(m);
  }
  void send(const std::string& ch, const thx_msgs::contact_t& m) override { contacts.push_back({ch, m.tick}); }
  void send(const std::string& ch, const thx_msgs::contact_batch_t& m) override { batches.emplace_back(ch, m); }
  void send(const std::string& ch, const thx_msgs::servo_stats_t& m) override { stats.emplace_back(ch, m); }

  std::size_t statesOn(const std::string& ch) const {
    std::size_t n = 0;
    for (const auto& s : states) n += s.channel == ch;
    return n;
  }
};

// Drives `ticks` servo ticks [first, first + ticks) through the table.
inline void runTicks(srv::SubscriptionTable& t, srv::MessageSink& sink, std::int64_t first, std::int64_t ticks) {
  thx_msgs::device_state_t d{};
  thx_msgs::contact_t c{};
  for (std::int64_t k = first; k < first + ticks; ++k) {
    d.tick = c.tick = k;
    d.utime = c.utime = k * 1000;
    t.onTick(d, c, k * 1000, sink);
  }
}

inline thx_msgs::subscribe_request_t request(const std::string& id, const std::string& stream, double rate_hz,
                                             bool batch = false, std::int64_t seq = 1) {
  thx_msgs::subscribe_request_t r{};
  r.seq = seq;
  r.client_id = id;
  r.stream = stream;
  r.action = thx_msgs::subscribe_request_t::ACTION_SUBSCRIBE;
  r.rate_hz = rate_hz;
  r.batch = batch;
  return r;
}

}  // namespace thx::test
