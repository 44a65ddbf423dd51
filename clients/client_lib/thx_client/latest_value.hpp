#pragma once
// LatestValue<M>: the newest decoded message of one stream, readable from any thread, with a
// count and the callback that runs on each one. Messages with strings and arrays are not
// trivially copyable, so this is a mutex (never taken by a real-time thread: a client's servo-like
// loop reads through its own copy), not rt::LatestSlot.
#include <cstdint>
#include <functional>
#include <mutex>
#include <optional>

namespace thx::client {

template <class M>
class LatestValue {
 public:
  using Callback = std::function<void(const M&, std::int64_t receipt_ns)>;

  void onMessage(Callback f) { callback_ = std::move(f); }
  // The receiving thread: stores, counts, then runs the callback.
  void deliver(const M& m, std::int64_t receipt_ns) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      latest_ = m;
      ++count_;
    }
    if (callback_) callback_(m, receipt_ns);
  }
  std::optional<M> latest() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return latest_;
  }
  std::uint64_t count() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return count_;
  }

 private:
  mutable std::mutex mutex_;
  std::optional<M> latest_;
  std::uint64_t count_ = 0;
  Callback callback_;
};

}  // namespace thx::client
