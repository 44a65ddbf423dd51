// FlightRecorder (server/flight_recorder.hpp): the dump writes, for each of the last ticks before
// a fault and in their order, every field of the TickRecord it names, as the servo recorded it;
// the recorder keeps a slim copy of each record, so a field that copy dropped would be written
// as zero.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "server/flight_recorder.hpp"
#include "tests/support/temp_dir.hpp"

namespace test_flight_recorder {

using namespace thx::srv;

namespace {

// A record whose every written field differs from the others' and from its neighbours'.
TickRecord recordOfTick(int k) {
  TickRecord r;
  const double b = 1.0 + k;
  r.tick = 1000 + k;
  r.missed = k % 3;
  r.wake_latency_ns = 1500 + k;
  r.compute_ns = 2500 + k;
  r.valid = k % 2 == 0;
  for (int a = 0; a < 3; ++a) {
    r.p_world[a] = 0.01 * b + 0.001 * a;
    r.v_world[a] = 0.2 * b + 0.01 * a;
    r.f_render[a] = 1.1 * b + 0.1 * a;
    r.f_client[a] = 2.1 * b + 0.1 * a;
    r.f_passive[a] = 3.1 * b + 0.1 * a;
    r.f_out[a] = 4.1 * b + 0.1 * a;
  }
  r.in_contact = k % 2 == 1;
  r.recovering = k % 3 == 2;
  r.num_planes = std::int8_t(1 + k % 4);
  r.depth_m = 1e-4 * b;
  r.pc_energy_j = 5e-3 * b;
  r.pc_damping_ns_per_m = 7.5 * b;
  r.safety_flags = 16u + unsigned(k);
  r.faults = 32u + unsigned(k);
  return r;
}

// The values the dump writes of a record, in its columns' order.
std::vector<double> columnsOf(const TickRecord& r) {
  std::vector<double> c{double(r.tick), double(r.missed), double(r.wake_latency_ns) / 1e3, double(r.compute_ns) / 1e3,
                        double(r.valid)};
  for (double x : r.p_world) c.push_back(x);
  for (double x : r.v_world) c.push_back(x);
  c.insert(c.end(), {double(r.in_contact), double(r.recovering), double(r.num_planes), r.depth_m});
  for (const double* f : {r.f_render, r.f_client, r.f_passive, r.f_out}) c.insert(c.end(), f, f + 3);
  c.insert(c.end(), {r.pc_energy_j, r.pc_damping_ns_per_m, double(r.safety_flags), double(r.faults)});
  return c;
}

std::vector<std::string> linesOf(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

}  // namespace

TEST(FlightRecorder, TheDumpWritesEveryNamedFieldOfTheLastTicksInOrder) {
  thx::test::TempDir dir("flight_recorder");
  FlightRecorder recorder(4);
  for (int k = 0; k < 7; ++k) recorder.record(recordOfTick(k));  // wraps: ticks 3..6 are kept
  recorder.freeze(kFaultForceBudget, 1006);
  recorder.record(recordOfTick(99));  // after the fault: into the other buffer, not the dump
  const std::string path = recorder.dumpPending(dir.path().string());
  EXPECT_EQ(path, dir.file("flight-tick1006-force-budget.csv"));
  const std::vector<std::string> lines = linesOf(path);
  ASSERT_EQ(lines.size(), 2u + 4u) << path;
  EXPECT_EQ(lines[0], "# flight record: 4 ticks before fault 'force-budget' at tick 1006");
  std::size_t header_columns = 1;
  for (char ch : lines[1]) header_columns += ch == ',';
  for (int row = 0; row < 4; ++row) {
    const std::vector<double> expected = columnsOf(recordOfTick(3 + row));
    ASSERT_EQ(expected.size(), header_columns);
    std::stringstream cells(lines[2 + std::size_t(row)]);
    std::string cell;
    for (std::size_t c = 0; c < expected.size(); ++c) {
      ASSERT_TRUE(std::getline(cells, cell, ',')) << "row " << row << " column " << c;
      // %.9g for positions, %.6g for the rest, %.3f for microseconds: the printed precision.
      EXPECT_NEAR(std::strtod(cell.c_str(), nullptr), expected[c], 1e-5 * std::abs(expected[c]) + 1e-12)
          << "row " << row << " column " << c;
    }
    EXPECT_FALSE(std::getline(cells, cell, ',')) << "row " << row << " has more columns than the header";
  }
  EXPECT_EQ(recorder.dumpPending(dir.path().string()), "");  // written once
}

}  // namespace test_flight_recorder
