// The servo's timing policy on a virtual clock: grid deadlines, late ticks, realignment after
// overruns (no catch-up burst), missed-tick accounting; the spin before a deadline.
#include <gtest/gtest.h>

#include <utility>
#include <vector>

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

// Behaviour only (never a timing bound): after each wait() the clock is at or past the deadline.
void expectWakesAtOrAfterEachDeadline(std::int64_t spin_ns) {
  MonotonicClock clock;
  Pacer pacer(clock, 200'000, spin_ns);
  pacer.start();
  for (int k = 0; k < 5; ++k) {
    const TickTiming t = pacer.wait();
    EXPECT_GE(t.wake_ns, t.deadline_ns);
    EXPECT_GE(clock.nowNs(), t.deadline_ns);
  }
}

TEST(Pacer, MonotonicClockSleepsUntilTheDeadline) { expectWakesAtOrAfterEachDeadline(0); }

// A clock that records how the pacer waits: a sleep, then a spin, each to its target.
class RecordingClock final : public Clock {
 public:
  std::int64_t nowNs() override { return now_; }
  void sleepUntilNs(std::int64_t t) override {
    calls.push_back({'s', t});
    if (t > now_) now_ = t;
  }
  void spinUntilNs(std::int64_t t) override {
    calls.push_back({'p', t});
    if (t > now_) now_ = t;
  }
  std::vector<std::pair<char, std::int64_t>> calls;

 private:
  std::int64_t now_ = 0;
};

TEST(Pacer, SpinsTheLastStretchBeforeEachDeadline) {
  RecordingClock clock;
  Pacer pacer(clock, 250'000, 100'000);  // 4 kHz, the last 100 us spun
  EXPECT_EQ(pacer.spinNs(), 100'000);
  pacer.start();
  const TickTiming t = pacer.wait();
  EXPECT_EQ(t.deadline_ns, 250'000);
  EXPECT_EQ(t.wake_latency_ns, 0);
  ASSERT_EQ(clock.calls.size(), 2u);
  EXPECT_EQ(clock.calls[0], std::make_pair('s', std::int64_t(150'000)));
  EXPECT_EQ(clock.calls[1], std::make_pair('p', std::int64_t(250'000)));
  // Without a spin it only sleeps, as before; a spin of a period or more is clamped below it.
  RecordingClock plain;
  Pacer sleeper(plain, 250'000);
  sleeper.start();
  sleeper.wait();
  ASSERT_EQ(plain.calls.size(), 1u);
  EXPECT_EQ(plain.calls[0], std::make_pair('s', std::int64_t(250'000)));
  EXPECT_EQ(Pacer(plain, 250'000, 400'000).spinNs(), 249'999);
  EXPECT_EQ(Pacer(plain, 250'000, -5).spinNs(), 0);
}

TEST(Pacer, MonotonicClockSpinsToTheDeadline) {
  expectWakesAtOrAfterEachDeadline(150'000);
  // A virtual clock's spin jumps like its sleep: lock-step never busy-waits.
  VirtualClock virtual_clock;
  Pacer lockstep(virtual_clock, 250'000, 100'000);
  lockstep.start();
  EXPECT_EQ(lockstep.wait().deadline_ns, 250'000);
  EXPECT_EQ(virtual_clock.nowNs(), 250'000);
}

}  // namespace test_pacer
