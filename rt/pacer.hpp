#pragma once
// Pacer: the servo's timing policy, isolated so it can be unit-tested (as ros2_control does).
//
// Deadlines sit on a fixed grid t0 + k * period. wait() sleeps until the next grid point.
// Missed-cycle policy (docs/design.md §4 rule 2): if the loop arrives after its deadline has
// passed by a whole period or more, it REALIGNS to the next grid point in the future (no catch-up
// burst) and reports how many grid points it skipped; the caller decides what to do with the
// missed ticks (the servo: server/missed_tick_policy.hpp). A tick less than a period late runs
// late and misses nothing; one a period late or more skips every grid point already past, so a
// skip is >= 2.
#include <cstdint>

#include "rt/clock.hpp"

namespace thx::rt {

struct TickTiming {
  std::int64_t tick = 0;             // index of this tick on the grid (skipped ticks count)
  std::int64_t deadline_ns = 0;      // the grid point this tick was scheduled for
  std::int64_t wake_ns = 0;          // when the loop actually resumed
  std::int64_t wake_latency_ns = 0;  // wake_ns - deadline_ns (>= 0)
  std::int64_t missed = 0;           // grid points skipped just before this tick
};

class Pacer {
 public:
  // spin_ns > 0: wait() sleeps until spin_ns before each deadline and spends the rest in a busy
  // wait (Clock::spinUntilNs). A kernel that wakes a sleeping thread late (a VM's idle vCPU) then
  // makes it late only by what exceeds spin_ns, at the cost of spin_ns of CPU every period. Clamped
  // to [0, period_ns).
  Pacer(Clock& clock, std::int64_t period_ns, std::int64_t spin_ns = 0)
      : clock_(clock), period_ns_(period_ns), spin_ns_(spin_ns < 0 ? 0 : spin_ns >= period_ns ? period_ns - 1 : spin_ns) {}

  // The first deadline is one period after now.
  void start();
  // Blocks until the next deadline; real-time safe.
  TickTiming wait();

  std::int64_t periodNs() const { return period_ns_; }
  std::int64_t spinNs() const { return spin_ns_; }
  std::int64_t totalMissed() const { return total_missed_; }

 private:
  Clock& clock_;
  std::int64_t period_ns_;
  std::int64_t spin_ns_;
  std::int64_t next_deadline_ns_ = 0;
  std::int64_t next_tick_ = 0;
  std::int64_t total_missed_ = 0;
};

}  // namespace thx::rt
