// The servo's timing policy on a virtual clock: grid deadlines, late ticks, realignment after
// overruns (no catch-up burst), missed-tick accounting.
#include <gtest/gtest.h>

#include "rt/pacer.hpp"

namespace test_pacer {

using namespace thx::rt;

namespace {
constexpr std::int64_t kPeriod = 1'000'000;  // 1 ms
}

TEST(Pacer, OnTimeTicksFollowTheGrid) {
  VirtualClock clock(5'000);
  Pacer pacer(clock, kPeriod);
  pacer.start();
  for (int k = 0; k < 100; ++k) {
    const TickTiming t = pacer.wait();
    EXPECT_EQ(t.tick, k);
    EXPECT_EQ(t.deadline_ns, 5'000 + (k + 1) * kPeriod);
    EXPECT_EQ(t.wake_ns, t.deadline_ns);
    EXPECT_EQ(t.wake_latency_ns, 0);
    EXPECT_EQ(t.missed, 0);
    clock.advance(300'000);  // compute time well inside the period
  }
  EXPECT_EQ(pacer.totalMissed(), 0);
}

TEST(Pacer, LateButWithinOnePeriodRunsImmediatelyWithoutMissing) {
  VirtualClock clock;
  Pacer pacer(clock, kPeriod);
  pacer.start();
  pacer.wait();              // tick 0 at 1 ms
  clock.advance(1'400'000);  // compute overran: now 2.4 ms, tick 1 was due at 2 ms
  const TickTiming t = pacer.wait();
  EXPECT_EQ(t.tick, 1);
  EXPECT_EQ(t.missed, 0);
  EXPECT_EQ(t.wake_latency_ns, 400'000);
  // The grid does not shift: tick 2 is still due at 3 ms.
  EXPECT_EQ(pacer.wait().deadline_ns, 3 * kPeriod);
}

TEST(Pacer, OverrunRealignsToTheNextGridPointWithoutBurst) {
  VirtualClock clock;
  Pacer pacer(clock, kPeriod);
  pacer.start();
  pacer.wait();              // tick 0 at 1 ms
  clock.advance(3'500'000);  // stalled: now 4.5 ms; ticks due at 2, 3 and 4 ms are gone
  const TickTiming t = pacer.wait();
  EXPECT_EQ(t.missed, 3);
  EXPECT_EQ(t.tick, 4);
  EXPECT_EQ(t.deadline_ns, 5 * kPeriod);
  EXPECT_EQ(t.wake_latency_ns, 0);
  EXPECT_EQ(pacer.totalMissed(), 3);
  // Afterwards the loop is back on the grid, one tick per period.
  const TickTiming next = pacer.wait();
  EXPECT_EQ(next.tick, 5);
  EXPECT_EQ(next.deadline_ns, 6 * kPeriod);
  EXPECT_EQ(next.missed, 0);
}

TEST(Pacer, MonotonicClockSleepsUntilTheDeadline) {
  // Behaviour only (never a timing bound): after wait() the clock is at or past the deadline.
  MonotonicClock clock;
  Pacer pacer(clock, 200'000);
  pacer.start();
  for (int k = 0; k < 5; ++k) {
    const TickTiming t = pacer.wait();
    EXPECT_GE(t.wake_ns, t.deadline_ns);
    EXPECT_GE(clock.nowNs(), t.deadline_ns);
  }
}

}  // namespace test_pacer
