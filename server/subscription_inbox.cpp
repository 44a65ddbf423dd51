#include "server/subscription_inbox.hpp"

#include <lcm/lcm-cpp.hpp>
#include <thx_msgs/protocol.hpp>

#include "rt/clock.hpp"

namespace thx::srv {

namespace {
std::int64_t monotonicNs() { return rt::monotonicNowNs(); }
}  // namespace

SubscriptionInbox::~SubscriptionInbox() { detach(); }

void SubscriptionInbox::attach(lcm::LCM& lcm) {
  detach();
  lcm_ = &lcm;
  // Untyped: the bytes come from any process on the bus (docs/messages.md §7.3).
  request_sub_ = lcm.subscribe(thx_msgs::kChannelSubscribe, &SubscriptionInbox::onRequest, this);
  heartbeat_sub_ = lcm.subscribe(thx_msgs::kChannelHeartbeat, &SubscriptionInbox::onHeartbeat, this);
  // A burst of clients (all re-subscribing after a restart) must not be cut at LCM's default 30.
  if (request_sub_) request_sub_->setQueueCapacity(512);
  if (heartbeat_sub_) heartbeat_sub_->setQueueCapacity(512);
}

void SubscriptionInbox::detach() {
  if (!lcm_) return;
  if (request_sub_) lcm_->unsubscribe(request_sub_);
  if (heartbeat_sub_) lcm_->unsubscribe(heartbeat_sub_);
  request_sub_ = heartbeat_sub_ = nullptr;
  lcm_ = nullptr;
}

void SubscriptionInbox::take(ControlMessages& out) {
  out.requests.clear();
  out.heartbeats.clear();
  std::lock_guard<std::mutex> lock(mutex_);
  std::swap(out.requests, queued_.requests);
  std::swap(out.heartbeats, queued_.heartbeats);
}

void SubscriptionInbox::onRequest(const lcm::ReceiveBuffer* rbuf, const std::string&) {
  thx_msgs::subscribe_request_t m;
  if (const std::string problem = decodeUntrusted(rbuf->data, rbuf->data_size, m); !problem.empty()) {
    undecodable_.fetch_add(1);
    problems_.report(thx_msgs::kChannelSubscribe, problem, monotonicNs());
    return;
  }
  push(m, monotonicNs());
}

void SubscriptionInbox::onHeartbeat(const lcm::ReceiveBuffer* rbuf, const std::string&) {
  thx_msgs::heartbeat_t m;
  if (const std::string problem = decodeUntrusted(rbuf->data, rbuf->data_size, m); !problem.empty()) {
    undecodable_.fetch_add(1);
    problems_.report(thx_msgs::kChannelHeartbeat, problem, monotonicNs());
    return;
  }
  push(m, monotonicNs());
}

void SubscriptionInbox::push(const thx_msgs::subscribe_request_t& m, std::int64_t received_ns) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (queued_.requests.size() >= kMaxQueued) {
    overflowed_.fetch_add(1);
    return;
  }
  queued_.requests.push_back({m, received_ns});
}

void SubscriptionInbox::push(const thx_msgs::heartbeat_t& m, std::int64_t received_ns) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (queued_.heartbeats.size() >= kMaxQueued) {
    overflowed_.fetch_add(1);
    return;
  }
  queued_.heartbeats.push_back({m, received_ns});
}

}  // namespace thx::srv
