// ReportInterval (device/vrpn/report_interval.hpp): the client device's measure of how often the
// server really reports, and how long a pose therefore stays fresh.
#include <gtest/gtest.h>

#include "device/vrpn/report_interval.hpp"

namespace test_report_interval {

using thx::vrpn::ReportInterval;

namespace {
constexpr std::int64_t kMs = 1'000'000;
}

TEST(VrpnReportInterval, NothingMeasuredKeepsTheConfiguredStaleness) {
  ReportInterval r;
  EXPECT_EQ(r.medianNs(), 0);
  EXPECT_EQ(r.freshForNs(5 * kMs), 5 * kMs);
  r.add(100 * kMs);  // one report: still no interval
  EXPECT_EQ(r.intervals(), 0);
  EXPECT_EQ(r.freshForNs(5 * kMs), 5 * kMs);
}

TEST(VrpnReportInterval, AFastServerKeepsTheConfiguredStaleness) {
  ReportInterval r;
  for (int i = 0; i < 40; ++i) r.add(i * kMs);  // 1 kHz
  EXPECT_EQ(r.medianNs(), kMs);
  EXPECT_TRUE(r.full());
  EXPECT_EQ(r.freshForNs(5 * kMs), 5 * kMs);
}

TEST(VrpnReportInterval, ASixtyHertzServerGetsOneAndAHalfIntervals) {
  ReportInterval r;
  const std::int64_t period = 16'666'667;
  for (int i = 0; i < 20; ++i) r.add(i * period);
  EXPECT_EQ(r.medianNs(), period);
  EXPECT_EQ(r.freshForNs(5 * kMs), period + period / 2);  // 25 ms
}

TEST(VrpnReportInterval, APauseOrABurstMovesTheMedianByOneRankOnly) {
  ReportInterval r;
  std::int64_t t = 0;
  for (int i = 0; i < 15; ++i) r.add(t += 10 * kMs);
  r.add(t += 1000 * kMs);  // the server stalled for a second
  EXPECT_EQ(r.medianNs(), 10 * kMs);
  r.add(t);  // two reports in one segment
  r.add(t);
  EXPECT_EQ(r.medianNs(), 10 * kMs);
}

TEST(VrpnReportInterval, ResetForgetsTheOldServer) {
  ReportInterval r;
  for (int i = 0; i < 20; ++i) r.add(i * 50 * kMs);
  r.reset();
  EXPECT_EQ(r.intervals(), 0);
  EXPECT_EQ(r.freshForNs(5 * kMs), 5 * kMs);
  r.add(2000 * kMs);
  r.add(2001 * kMs);
  EXPECT_EQ(r.medianNs(), kMs);  // not an interval across the reconnect
}

TEST(VrpnReportInterval, AClockThatStepsBackCountsAsZero) {
  ReportInterval r;
  r.add(10 * kMs);
  r.add(5 * kMs);
  EXPECT_EQ(r.medianNs(), 0);
}

}  // namespace test_report_interval
