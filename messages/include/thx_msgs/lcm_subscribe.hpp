#pragma once
// Subscribing to LCM, telling whether it worked. LCM's C++ subscribe() always returns a
// Subscription, even when the C library refused: udpm sets up its receive socket on the first
// subscribe, and when that bind fails (another program holds the port without SO_REUSEADDR, e.g.
// an ephemeral UDP socket in 32768..60999) the Subscription's C handle is null, and the first
// setQueueCapacity() on it reads through null (LCM 1.3.1, lcm-cpp-impl.hpp). `subscribeUntyped`
// returns nullptr instead, so the caller can say which URL and channel could not be heard.
#include <lcm/lcm-cpp.hpp>
#include <string>

namespace thx_msgs {

namespace detail {
// The C handle is protected; a member pointer named through a derived class reaches it legally.
struct SubscriptionHandle : lcm::Subscription {
  static lcm_subscription_t* of(lcm::Subscription* s) { return s->*(&SubscriptionHandle::c_subs); }
};
}  // namespace detail

// nullptr when LCM could not subscribe. The refused Subscription stays with the LCM object (which
// deletes it): lcm_unsubscribe() on a null handle is not safe in every LCM version.
template <class Handler>
lcm::Subscription* subscribeUntyped(lcm::LCM& lcm, const std::string& channel,
                                    void (Handler::*method)(const lcm::ReceiveBuffer*, const std::string&),
                                    Handler* handler, int queue_capacity = 0) {
  lcm::Subscription* s = lcm.subscribe(channel, method, handler);
  if (!s || !detail::SubscriptionHandle::of(s)) return nullptr;
  if (queue_capacity > 0) s->setQueueCapacity(queue_capacity);
  return s;
}

}  // namespace thx_msgs
