#include "rt/pacer.hpp"

namespace thx::rt {

void Pacer::start() {
  next_deadline_ns_ = clock_.nowNs() + period_ns_;
  next_tick_ = 0;
  total_missed_ = 0;
}

TickTiming Pacer::wait() {
  TickTiming t;
  std::int64_t now = clock_.nowNs();
  if (now >= next_deadline_ns_ + period_ns_) {
    // Overran by a whole period or more: every grid point up to now is missed; realign to the
    // first one still in the future instead of bursting through the backlog.
    const std::int64_t skipped = (now - next_deadline_ns_) / period_ns_ + 1;
    next_deadline_ns_ += skipped * period_ns_;
    next_tick_ += skipped;
    t.missed = skipped;
    total_missed_ += skipped;
  }
  if (spin_ns_ > 0) {
    clock_.sleepUntilNs(next_deadline_ns_ - spin_ns_);
    clock_.spinUntilNs(next_deadline_ns_);
  } else {
    clock_.sleepUntilNs(next_deadline_ns_);
  }
  now = clock_.nowNs();
  t.tick = next_tick_;
  t.deadline_ns = next_deadline_ns_;
  t.wake_ns = now;
  t.wake_latency_ns = now > next_deadline_ns_ ? now - next_deadline_ns_ : 0;
  next_deadline_ns_ += period_ns_;
  ++next_tick_;
  return t;
}

}  // namespace thx::rt
