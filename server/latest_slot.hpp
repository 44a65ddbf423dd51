#pragma once
// Latest-value slot (a seqlock): how commands enter the servo thread. One writer (a receiver
// thread) overwrites; the servo reads the newest complete value without ever waiting. A read
// that races a write retries a bounded number of times and otherwise keeps the previous value.
#include <atomic>
#include <cstdint>
#include <type_traits>

namespace thx::srv {

template <class T>
class LatestSlot {
  static_assert(std::is_trivially_copyable_v<T>, "values cross threads by copy");

 public:
  void write(const T& value) {
    const std::uint32_t s = seq_.load(std::memory_order_relaxed);
    seq_.store(s + 1, std::memory_order_relaxed);  // odd: write in progress
    std::atomic_thread_fence(std::memory_order_release);
    copyIn(value);
    seq_.store(s + 2, std::memory_order_release);
  }

  // Real-time safe. Returns true and fills `out` if a complete value newer than `last_seq` was
  // read; false leaves `out` untouched (nothing new, or the writer kept interfering).
  bool readIfNewer(T& out, std::uint32_t& last_seq) const {
    for (int attempt = 0; attempt < 4; ++attempt) {
      const std::uint32_t before = seq_.load(std::memory_order_acquire);
      if (before & 1u) continue;
      if (before == last_seq) return false;
      T copy;
      copyOut(copy);
      std::atomic_thread_fence(std::memory_order_acquire);
      if (seq_.load(std::memory_order_relaxed) == before) {
        out = copy;
        last_seq = before;
        return true;
      }
    }
    return false;
  }

 private:
  // Word-wise relaxed atomic copies keep the racing reads defined behaviour.
  static constexpr std::size_t kWords = (sizeof(T) + sizeof(std::uint64_t) - 1) / sizeof(std::uint64_t);
  void copyIn(const T& value) {
    std::uint64_t words[kWords] = {};
    __builtin_memcpy(words, &value, sizeof(T));
    for (std::size_t k = 0; k < kWords; ++k) data_[k].store(words[k], std::memory_order_relaxed);
  }
  void copyOut(T& value) const {
    std::uint64_t words[kWords];
    for (std::size_t k = 0; k < kWords; ++k) words[k] = data_[k].load(std::memory_order_relaxed);
    __builtin_memcpy(&value, words, sizeof(T));
  }

  std::atomic<std::uint32_t> seq_{0};
  std::atomic<std::uint64_t> data_[kWords] = {};
};

}  // namespace thx::srv
