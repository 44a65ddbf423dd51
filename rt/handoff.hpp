#pragma once
// Handoff: how a large object built off the real-time thread (a new scene's surface, hundreds of
// megabytes of texture) reaches it, and how the real-time thread says it is done with the old
// one, without the real-time thread ever allocating, freeing, locking or waiting.
//
// One owner thread and one real-time thread; one object in flight at a time:
//   owner:  offer(p)      Idle -> Offered      (false, nothing changes, unless Idle)
//   rt:     take()        Offered -> Taken     returns p; null in every other state
//   rt:     complete()    Taken -> Done        "p is in use now; the one it replaced is free"
//   owner:  reclaim()     Done -> Idle         true once: the owner may free the replaced object
// The owner keeps ownership throughout (the handoff holds a plain pointer): it frees the replaced
// object after reclaim() and only then offers the next. A taken object the rt thread never
// completes stays Taken; the owner sees that (state()) and must not free anything meanwhile.
// The acquire/release pairs make the object's construction visible to the rt thread before it
// reads the pointer, and the rt thread's last reads of the replaced object happen before the
// owner frees it.
#include <atomic>
#include <cstdint>

namespace thx::rt {

template <class T>
class Handoff {
 public:
  enum class State : std::uint8_t { Idle, Offered, Taken, Done };

  // Owner thread.
  bool offer(T* object) {
    if (object == nullptr || state_.load(std::memory_order_acquire) != State::Idle) return false;
    object_ = object;
    state_.store(State::Offered, std::memory_order_release);
    return true;
  }
  bool reclaim() {
    State done = State::Done;
    return state_.compare_exchange_strong(done, State::Idle, std::memory_order_acq_rel);
  }
  State state() const { return state_.load(std::memory_order_acquire); }

  // Real-time thread. Wait-free, no allocation.
  T* take() {
    State offered = State::Offered;
    if (!state_.compare_exchange_strong(offered, State::Taken, std::memory_order_acq_rel)) return nullptr;
    return object_;
  }
  void complete() {
    State taken = State::Taken;
    state_.compare_exchange_strong(taken, State::Done, std::memory_order_acq_rel);
  }

 private:
  std::atomic<State> state_{State::Idle};
  T* object_ = nullptr;  // written by the owner before Offered, read by rt after Offered
};

}  // namespace thx::rt
