// Flight-record files are capped in count and in rate (issue 12): decisions on device time, so
// the same faults always give the same files.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "base/error.hpp"
#include "server/flight_dump_limits.hpp"
#include "server/flight_recorder.hpp"

namespace test_flight_dump_limits {

namespace fs = std::filesystem;
using namespace thx::srv;

namespace {

class FlightDumpLimitsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("thx_flight_limits_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // A fault at `tick` after a few recorded ticks, then the publisher's step.
  FlightDump faultAt(FlightRecorder& recorder, FlightDumpGate& gate, std::int64_t tick) {
    for (std::int64_t t = tick - 3; t <= tick; ++t) {
      TickRecord r;
      r.tick = t;
      recorder.record(r);
    }
    recorder.freeze(kFaultMissedTicks, tick);
    return dumpWithinLimits(recorder, gate, dir_.string());
  }

  std::size_t files() const {
    std::size_t n = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir_)) ++n;
    return n;
  }

  fs::path dir_;
};

}  // namespace

TEST_F(FlightDumpLimitsTest, RateCapSkipsFaultsTooSoonAfterTheLastWrittenOne) {
  FlightRecorder recorder(100);
  FlightDumpGate gate({.max_files = 20, .min_interval_s = 10.0}, 1e-3);
  EXPECT_EQ(faultAt(recorder, gate, 1000).outcome, FlightDumpOutcome::Written);
  EXPECT_EQ(faultAt(recorder, gate, 1500).outcome, FlightDumpOutcome::OverRate);    // 0.5 s later
  EXPECT_EQ(faultAt(recorder, gate, 10999).outcome, FlightDumpOutcome::OverRate);   // 9.999 s
  const FlightDump later = faultAt(recorder, gate, 11000);                          // 10 s: written
  EXPECT_EQ(later.outcome, FlightDumpOutcome::Written);
  EXPECT_EQ(later.path, dir_.string() + "/flight-tick11000-missed-ticks.csv");
  EXPECT_TRUE(fs::exists(later.path));
  // A refused flight is dropped at once: the recorder is free for the next fault.
  EXPECT_FALSE(recorder.pendingTick().has_value());
  EXPECT_EQ(recorder.faultsNotFrozen(), 0u);
  EXPECT_EQ(gate.written(), 2u);
  EXPECT_EQ(gate.overRate(), 2u);
  EXPECT_EQ(gate.overCount(), 0u);
  EXPECT_EQ(files(), 2u);
}

TEST_F(FlightDumpLimitsTest, CountCapBoundsTheFilesOfARunThatFaultsForAnHour) {
  // One fault every 2 s for an hour (1800 faults), the load case: 20 files at most.
  FlightRecorder recorder(10);
  FlightDumpGate gate(FlightDumpLimits{}, 1e-3);  // the defaults: 20 files, 10 s apart
  std::vector<FlightDumpOutcome> outcomes;
  for (std::int64_t tick = 2000; tick <= 3'600'000; tick += 2000) outcomes.push_back(faultAt(recorder, gate, tick).outcome);
  EXPECT_EQ(outcomes.size(), 1800u);
  EXPECT_EQ(gate.written(), 20u);
  EXPECT_EQ(files(), 20u);
  // Every fifth fault is 10 s after the last written one until the cap; then none is written.
  EXPECT_EQ(gate.overRate(), 4u * 19u);  // the four between each two of the 20 files
  EXPECT_EQ(gate.overCount(), 1800u - 20u - 4u * 19u);
  EXPECT_EQ(outcomes[0], FlightDumpOutcome::Written);
  EXPECT_EQ(outcomes[1], FlightDumpOutcome::OverRate);
  EXPECT_EQ(outcomes[5], FlightDumpOutcome::Written);
  EXPECT_EQ(outcomes[95], FlightDumpOutcome::Written);    // the 20th, 190 s after the first
  EXPECT_EQ(outcomes[96], FlightDumpOutcome::OverCount);  // the cap holds from here on
  EXPECT_EQ(outcomes.back(), FlightDumpOutcome::OverCount);
}

TEST_F(FlightDumpLimitsTest, ZeroMaxWritesNothingAndZeroIntervalWritesEveryFault) {
  FlightRecorder recorder(10);
  FlightDumpGate none({.max_files = 0, .min_interval_s = 10.0}, 1e-3);
  EXPECT_EQ(faultAt(recorder, none, 100).outcome, FlightDumpOutcome::OverCount);
  EXPECT_EQ(files(), 0u);
  FlightDumpGate every({.max_files = 3, .min_interval_s = 0.0}, 1e-3);
  for (std::int64_t tick : {200, 201, 202}) EXPECT_EQ(faultAt(recorder, every, tick).outcome, FlightDumpOutcome::Written);
  EXPECT_EQ(faultAt(recorder, every, 203).outcome, FlightDumpOutcome::OverCount);
  EXPECT_EQ(files(), 3u);
  // Nothing pending: nothing decided, nothing counted.
  EXPECT_EQ(dumpWithinLimits(recorder, every, dir_.string()).outcome, FlightDumpOutcome::Nothing);
  EXPECT_EQ(every.overCount(), 1u);
}

TEST_F(FlightDumpLimitsTest, BadLimitsAreRefusedNamingTheField) {
  try {
    FlightDumpGate({.max_files = 1, .min_interval_s = -1.0}, 1e-3);
    FAIL() << "a negative interval was accepted";
  } catch (const thx::Error& e) {
    EXPECT_NE(std::string(e.what()).find("min_interval_s = -1"), std::string::npos) << e.what();
  }
  EXPECT_THROW(FlightDumpGate(FlightDumpLimits{}, 0.0), thx::Error);
}

}  // namespace test_flight_dump_limits
