#include "server/subscription_inbox.hpp"

#include <cstdio>

#include <lcm/lcm-cpp.hpp>
#include <thx_msgs/lcm_subscribe.hpp>
#include <thx_msgs/protocol.hpp>

#include "rt/clock.hpp"

namespace thx::srv {

namespace {
std::int64_t monotonicNs() { return rt::monotonicNowNs(); }
}  // namespace

SubscriptionInbox::~SubscriptionInbox() { detach(); }

void SubscriptionInbox::attach(lcm::LCM& lcm) {
  for (const Attached& a : attached_) {
    if (a.lcm == &lcm) return;
  }
  Attached a;
  a.lcm = &lcm;
  // Untyped: the bytes come from any process on the bus (docs/messages.md §7.3).
  // A burst of clients (all re-subscribing after a restart) must not be cut at LCM's default 30.
  constexpr int kQueue = 512;
  a.subs[0] = thx_msgs::subscribeUntyped(lcm, thx_msgs::kChannelSubscribe, &SubscriptionInbox::onRequest, this, kQueue);
  a.subs[1] = thx_msgs::subscribeUntyped(lcm, thx_msgs::kChannelHeartbeat, &SubscriptionInbox::onHeartbeat, this, kQueue);
  a.subs[2] = thx_msgs::subscribeUntyped(lcm, thx_msgs::kChannelCommand, &SubscriptionInbox::onCommand, this, kQueue);
  if (!a.subs[0] || !a.subs[1] || !a.subs[2]) {
    std::fprintf(stderr,
                 "hapticd: warning: LCM could not listen for %s, %s and %s (its receive socket did not bind: is "
                 "the port held by another program?): clients cannot subscribe there\n",
                 thx_msgs::kChannelSubscribe, thx_msgs::kChannelHeartbeat, thx_msgs::kChannelCommand);
  }
  attached_.push_back(a);
}

void SubscriptionInbox::detach() {
  for (Attached& a : attached_) {
    for (lcm::Subscription* sub : a.subs) {
      if (sub) a.lcm->unsubscribe(sub);
    }
  }
  attached_.clear();
}

void SubscriptionInbox::take(ControlMessages& out) {
  out.requests.clear();
  out.heartbeats.clear();
  out.commands.clear();
  std::lock_guard<std::mutex> lock(mutex_);
  std::swap(out.requests, queued_.requests);
  std::swap(out.heartbeats, queued_.heartbeats);
  std::swap(out.commands, queued_.commands);
}

// Decodes one message of type T, or counts and reports why the bytes are not one.
template <class T>
void SubscriptionInbox::receive(const lcm::ReceiveBuffer* rbuf, const char* channel) {
  T m;
  if (const std::string problem = decodeUntrusted(rbuf->data, rbuf->data_size, m); !problem.empty()) {
    undecodable_.fetch_add(1);
    problems_.report(channel, problem, monotonicNs());
    return;
  }
  push(m, monotonicNs());
}

void SubscriptionInbox::onRequest(const lcm::ReceiveBuffer* rbuf, const std::string&) {
  receive<thx_msgs::subscribe_request_t>(rbuf, thx_msgs::kChannelSubscribe);
}
void SubscriptionInbox::onHeartbeat(const lcm::ReceiveBuffer* rbuf, const std::string&) {
  receive<thx_msgs::heartbeat_t>(rbuf, thx_msgs::kChannelHeartbeat);
}
void SubscriptionInbox::onCommand(const lcm::ReceiveBuffer* rbuf, const std::string&) {
  receive<thx_msgs::server_command_t>(rbuf, thx_msgs::kChannelCommand);
}

template <class Queue, class T>
void SubscriptionInbox::enqueue(Queue& queue, const T& m, std::int64_t received_ns) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (queue.size() >= kMaxQueued) {
    overflowed_.fetch_add(1);
    return;
  }
  queue.push_back({m, received_ns});
}

void SubscriptionInbox::push(const thx_msgs::subscribe_request_t& m, std::int64_t received_ns) {
  enqueue(queued_.requests, m, received_ns);
}
void SubscriptionInbox::push(const thx_msgs::heartbeat_t& m, std::int64_t received_ns) {
  enqueue(queued_.heartbeats, m, received_ns);
}
void SubscriptionInbox::push(const thx_msgs::server_command_t& m, std::int64_t received_ns) {
  enqueue(queued_.commands, m, received_ns);
}

}  // namespace thx::srv
