#pragma once
// ReportInterval: how often a VRPN server really sends tracker reports, measured from their
// arrival times, and how long a pose may therefore count as fresh. Used by the client device's
// I/O thread (plain data, no allocation, not thread-safe).
//
// Why: a stock vrpn_Phantom reports at its vrpn.cfg rate (e.g. 60 Hz) until it honours our
// set_update_rate, and perhaps never. A fixed 5 ms staleness would then call most servo ticks
// invalid and the safety stage would switch the force off. So a pose is fresh for
// max(configured staleness, 1.5 x the typical interval): the device keeps working, forces
// follow the pen in steps of that interval, and the owner warns once.
//
// The typical interval is the median of the last kWindow intervals, not their mean: one long
// pause (a stalled server) or a few reports coalesced into one TCP segment shift the median by
// one rank, not by their size. A true stall still ends freshness after 1.5 intervals.
#include <algorithm>
#include <array>
#include <cstdint>

namespace thx::vrpn {

class ReportInterval {
 public:
  static constexpr int kWindow = 15;

  // A new connection: forget the old server's timing.
  void reset() {
    count_ = 0;
    next_ = 0;
    last_ns_ = -1;
  }

  // A report arrived at `now_ns` (a monotonic clock).
  void add(std::int64_t now_ns) {
    if (last_ns_ >= 0) {
      intervals_[std::size_t(next_)] = std::max<std::int64_t>(0, now_ns - last_ns_);
      next_ = (next_ + 1) % kWindow;
      count_ = std::min(count_ + 1, kWindow);
    }
    last_ns_ = now_ns;
  }

  // Intervals measured so far on this connection (at most kWindow).
  int intervals() const { return count_; }
  bool full() const { return count_ == kWindow; }

  // The median interval, or 0 before two reports arrived.
  std::int64_t medianNs() const {
    if (count_ == 0) return 0;
    std::array<std::int64_t, kWindow> sorted = intervals_;
    const auto end = sorted.begin() + count_;
    const auto mid = sorted.begin() + count_ / 2;
    std::nth_element(sorted.begin(), mid, end);
    return *mid;
  }

  // How long a pose stays fresh: max(configured, 1.5 x the median interval).
  std::int64_t freshForNs(std::int64_t configured_ns) const {
    return std::max(configured_ns, medianNs() + medianNs() / 2);
  }

 private:
  std::array<std::int64_t, kWindow> intervals_{};
  int count_ = 0;
  int next_ = 0;
  std::int64_t last_ns_ = -1;
};

}  // namespace thx::vrpn
