#pragma once
// Single-producer single-consumer ring of trivially copyable records: how tick snapshots leave
// the servo thread. The producer never blocks and never allocates: when the ring is full the new
// record is dropped and counted (the consumer is late; the servo must not wait for it).
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <type_traits>

namespace thx::rt {

template <class T>
class SpscRing {
  static_assert(std::is_trivially_copyable_v<T>, "records cross threads by copy");

 public:
  // capacity is rounded up to a power of two; memory is allocated here, never later.
  explicit SpscRing(std::size_t capacity) {
    std::size_t c = 1;
    while (c < capacity) c <<= 1;
    mask_ = c - 1;
    slots_ = std::make_unique<T[]>(c);
  }

  // Producer side (real-time safe). Returns false (and counts a drop) when full.
  bool push(const T& value) {
    const std::uint64_t head = head_.load(std::memory_order_relaxed);
    if (head - tail_.load(std::memory_order_acquire) > mask_) {
      dropped_.store(dropped_.load(std::memory_order_relaxed) + 1, std::memory_order_relaxed);
      return false;
    }
    slots_[head & mask_] = value;
    head_.store(head + 1, std::memory_order_release);
    return true;
  }

  // Consumer side.
  bool pop(T& out) {
    const std::uint64_t tail = tail_.load(std::memory_order_relaxed);
    if (tail == head_.load(std::memory_order_acquire)) return false;
    out = slots_[tail & mask_];
    tail_.store(tail + 1, std::memory_order_release);
    return true;
  }

  // Consumer side: the oldest record without removing it (null when empty); valid until pop().
  const T* front() const {
    const std::uint64_t tail = tail_.load(std::memory_order_relaxed);
    if (tail == head_.load(std::memory_order_acquire)) return nullptr;
    return &slots_[tail & mask_];
  }

  std::size_t capacity() const { return mask_ + 1; }
  // Records waiting (exact from either side; approximate from a third thread).
  std::size_t size() const {
    return std::size_t(head_.load(std::memory_order_acquire) - tail_.load(std::memory_order_acquire));
  }
  std::uint64_t dropped() const { return dropped_.load(std::memory_order_relaxed); }

 private:
  std::unique_ptr<T[]> slots_;
  std::size_t mask_ = 0;
  alignas(64) std::atomic<std::uint64_t> head_{0};
  alignas(64) std::atomic<std::uint64_t> tail_{0};
  alignas(64) std::atomic<std::uint64_t> dropped_{0};
};

}  // namespace thx::rt
