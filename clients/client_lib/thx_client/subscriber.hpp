#pragma once
// Subscriber<M>: a typed latest-value subscriber for a channel anyone publishes on without a
// subscription handshake (the physics client's THX_PHYSICS_* channels, hapticd's THX_HELLO).
// Bytes are decoded with thx_msgs::try_decode (never trusting lengths); what does not decode is
// counted and handed to the error callback. hapticd's per-client streams are asked for through
// Client::subscribe, which delivers them through the same LatestValue.
//
//   thx::client::Subscriber<thx_msgs::physics_poses_t> poses(lcm);  // THX_PHYSICS_POSES
//   poses.onMessage([](const auto& m, std::int64_t) { draw(m); });
//   poses.onError([](const DecodeError& e) { warn(e.message()); });
//
// Callbacks run in the thread that calls lcm.handle*() (the client's poll()); latest() and the
// counters from any thread.
#include <atomic>
#include <cstdint>
#include <lcm/lcm-cpp.hpp>
#include <string>
#include <thx_msgs/hello_t.hpp>
#include <thx_msgs/physics_contacts_t.hpp>
#include <thx_msgs/physics_impact_t.hpp>
#include <thx_msgs/physics_poses_t.hpp>
#include <thx_msgs/lcm_subscribe.hpp>
#include <thx_msgs/protocol.hpp>

#include "rt/clock.hpp"
#include "thx_client/decode_error.hpp"
#include "thx_client/latest_value.hpp"

namespace thx::client {

// The channel each broadcast type travels on.
template <class M>
struct BroadcastChannel;
template <>
struct BroadcastChannel<thx_msgs::physics_poses_t> {
  static constexpr const char* name = thx_msgs::kChannelPhysicsPoses;
};
template <>
struct BroadcastChannel<thx_msgs::physics_impact_t> {
  static constexpr const char* name = thx_msgs::kChannelPhysicsImpact;
};
template <>
struct BroadcastChannel<thx_msgs::physics_contacts_t> {
  static constexpr const char* name = thx_msgs::kChannelPhysicsContacts;
};
template <>
struct BroadcastChannel<thx_msgs::hello_t> {
  static constexpr const char* name = thx_msgs::kChannelHello;
};

template <class M>
class Subscriber {
 public:
  // queue_capacity: LCM's queue for this channel (its default, 30, drops bursts of impacts).
  explicit Subscriber(lcm::LCM& lcm, std::string channel = BroadcastChannel<M>::name, int queue_capacity = 64)
      : lcm_(lcm), channel_(std::move(channel)) {
    sub_ = thx_msgs::subscribeUntyped(lcm_, channel_, &Subscriber::onBytes, this, queue_capacity);
  }
  ~Subscriber() {
    if (sub_) lcm_.unsubscribe(sub_);
  }
  Subscriber(const Subscriber&) = delete;
  Subscriber& operator=(const Subscriber&) = delete;

  void onMessage(typename LatestValue<M>::Callback f) { value_.onMessage(std::move(f)); }
  void onError(DecodeErrorHandler f) { on_error_ = std::move(f); }

  std::optional<M> latest() const { return value_.latest(); }
  std::uint64_t received() const { return value_.count(); }
  std::uint64_t undecodable() const { return undecodable_.load(); }
  const std::string& channel() const { return channel_; }
  // False when LCM could not subscribe (its receive socket did not bind): nothing will arrive.
  bool listening() const { return sub_ != nullptr; }

  // Public for LCM's callback.
  void onBytes(const lcm::ReceiveBuffer* rbuf, const std::string& channel) {
    M m;
    if (thx_msgs::try_decode(rbuf->data, rbuf->data_size, m) < 0) {
      ++undecodable_;
      if (on_error_) on_error_(DecodeError{channel, M::getTypeName(), std::size_t(rbuf->data_size)});
      return;
    }
    value_.deliver(m, rt::monotonicNowNs());
  }

 private:
  lcm::LCM& lcm_;
  std::string channel_;
  lcm::Subscription* sub_ = nullptr;
  LatestValue<M> value_;
  std::atomic<std::uint64_t> undecodable_{0};
  DecodeErrorHandler on_error_;
};

using PhysicsPosesSubscriber = Subscriber<thx_msgs::physics_poses_t>;
using PhysicsImpactSubscriber = Subscriber<thx_msgs::physics_impact_t>;
using PhysicsContactsSubscriber = Subscriber<thx_msgs::physics_contacts_t>;
using HelloSubscriber = Subscriber<thx_msgs::hello_t>;

}  // namespace thx::client
