// Clocks: the virtual clock only moves when told (lock-step tests); the monotonic one sleeps to
// absolute deadlines and never goes back.
#include <gtest/gtest.h>

#include "rt/clock.hpp"

namespace test_clock {

using namespace thx::rt;

TEST(VirtualClock, SleepingJumpsToTheDeadlineAndNeverBack) {
  VirtualClock clock(1'000);
  EXPECT_EQ(clock.nowNs(), 1'000);
  clock.sleepUntilNs(5'000);
  EXPECT_EQ(clock.nowNs(), 5'000);
  clock.sleepUntilNs(2'000);  // a deadline in the past returns at once
  EXPECT_EQ(clock.nowNs(), 5'000);
  clock.advance(250);
  EXPECT_EQ(clock.nowNs(), 5'250);
}

TEST(MonotonicClock, SleepsAtLeastUntilTheDeadline) {
  MonotonicClock clock;
  const std::int64_t start = clock.nowNs();
  EXPECT_GE(start, 0);
  const std::int64_t deadline = start + 2'000'000;
  clock.sleepUntilNs(deadline);
  EXPECT_GE(clock.nowNs(), deadline);  // how much later is a benchmark's question (bench_latency)
  EXPECT_GE(monotonicNowNs(), deadline);
}

TEST(MonotonicClock, AgreesWithTheFreeFunction) {
  MonotonicClock clock;
  const std::int64_t a = monotonicNowNs(), b = clock.nowNs(), c = monotonicNowNs();
  EXPECT_LE(a, b);
  EXPECT_LE(b, c);
}

}  // namespace test_clock
