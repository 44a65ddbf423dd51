#include "server/latency_histogram.hpp"

#include <cmath>

namespace thx::srv {

double LatencyHistogram::quantileUs(double q) const {
  const std::uint64_t n = count();
  if (n == 0) return 0.0;
  // The smallest bin whose cumulative count reaches ceil(q * n) samples.
  const auto target = std::uint64_t(std::ceil(q * double(n)));
  std::uint64_t seen = 0;
  for (int b = 0; b < kBins; ++b) {
    seen += bins_[b].load(std::memory_order_relaxed);
    if (seen >= target && seen > 0) {
      const double max_us = double(maxNs()) / 1000.0;
      return b == kBins - 1 ? max_us : std::fmin(upperEdgeUs(b), max_us);
    }
  }
  return double(maxNs()) / 1000.0;
}

void LatencyHistogram::reset() {
  for (auto& b : bins_) b.store(0, std::memory_order_relaxed);
  count_.store(0, std::memory_order_relaxed);
  max_ns_.store(0, std::memory_order_relaxed);
}

}  // namespace thx::srv
