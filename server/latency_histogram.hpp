#pragma once
// A fixed-bin histogram of durations for tick statistics: 0.1 us bins up to 100 us, 10 us bins
// up to 10 ms, one overflow bin. Written by the servo thread only (plain relaxed load+store, no
// read-modify-write), readable from any thread at any time (values may be a tick stale).
#include <atomic>
#include <cstdint>

namespace thx::srv {

class LatencyHistogram {
 public:
  static constexpr int kFineBins = 1000;    // 0.1 us each, [0, 100 us)
  static constexpr int kCoarseBins = 990;   // 10 us each, [100 us, 10 ms)
  static constexpr int kBins = kFineBins + kCoarseBins + 1;

  void add(std::int64_t ns) {
    const int bin = binOf(ns);
    bins_[bin].store(bins_[bin].load(std::memory_order_relaxed) + 1, std::memory_order_relaxed);
    count_.store(count_.load(std::memory_order_relaxed) + 1, std::memory_order_relaxed);
    if (ns > max_ns_.load(std::memory_order_relaxed)) max_ns_.store(ns, std::memory_order_relaxed);
  }

  std::uint64_t count() const { return count_.load(std::memory_order_relaxed); }
  std::int64_t maxNs() const { return max_ns_.load(std::memory_order_relaxed); }
  // Upper edge of the bin holding the q-quantile (q in [0, 1]), in microseconds; the overflow bin
  // reports the exact maximum. 0 when empty.
  double quantileUs(double q) const;
  void reset();

 private:
  static int binOf(std::int64_t ns) {
    if (ns < 0) ns = 0;
    if (ns < 100'000) return int(ns / 100);
    if (ns < 10'000'000) return kFineBins + int((ns - 100'000) / 10'000);
    return kBins - 1;
  }
  static double upperEdgeUs(int bin) {
    if (bin < kFineBins) return (bin + 1) * 0.1;
    return 100.0 + (bin - kFineBins + 1) * 10.0;
  }

  std::atomic<std::uint64_t> bins_[kBins] = {};
  std::atomic<std::uint64_t> count_{0};
  std::atomic<std::int64_t> max_ns_{0};
};

}  // namespace thx::srv
