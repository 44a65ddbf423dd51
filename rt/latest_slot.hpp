#pragma once
// LatestSlot: a single-writer, any-reader latest-value slot (a seqlock): how plain data enters the
// servo thread (client forces from hapticd's receiver, VRPN reports from the device's I/O thread).
// The writer never waits; a reader never waits either: a read that races a write retries a
// bounded number of times and otherwise reports failure, leaving `out` untouched (the caller
// keeps its previous value). No allocation, no locks.
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <type_traits>

namespace thx::rt {

template <class T>
class LatestSlot {
  static_assert(std::is_trivially_copyable_v<T>, "values cross threads by copy");

 public:
  // One writer thread only.
  void write(const T& value) {
    const std::uint32_t s = seq_.load(std::memory_order_relaxed);
    seq_.store(s + 1, std::memory_order_relaxed);  // odd: write in progress
    std::atomic_thread_fence(std::memory_order_release);
    copyIn(value);
    seq_.store(s + 2, std::memory_order_release);
  }

  // True and `out` filled with the newest complete value if one newer than `last_seq` was read.
  bool readIfNewer(T& out, std::uint32_t& last_seq) const {
    for (int attempt = 0; attempt < 8; ++attempt) {
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

  // Sequence of the last completed write (0: never written).
  std::uint32_t sequence() const { return seq_.load(std::memory_order_acquire) & ~1u; }

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

}  // namespace thx::rt
