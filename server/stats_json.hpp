#pragma once
// hapticd's end-of-run statistics: the --stats-json file (documented in docs/hapticd.md) and the
// summary printed to the terminal.
#include <cstdio>
#include <string>
#include <vector>

#include "server/latency_histogram.hpp"
#include "server/missed_tick_policy.hpp"
#include "server/process_memory.hpp"
#include "server/publisher.hpp"
#include "server/realtime.hpp"
#include "server/safety.hpp"
#include "server/servo.hpp"
#include "server/servo_rig.hpp"

namespace thx::srv {

// One device of several (issue 30): its own servo's counters.
struct DeviceSummary {
  std::string name;
  ServoCounters servo;
  MissedTickCounters missed_policy;
  SafetyCounters safety;
  std::uint64_t passivity_active_ticks = 0;
  double compute_p99_us = 0.0;  // its own part of each tick
};

struct RunSummary {
  std::string scene;
  bool lockstep = false;
  bool crease = true;
  bool passivity = true;
  std::string tool = "point";  // what the servo renders the pen as: "point", or "capsule L x R mm"
  double stiffness_n_per_m = 0.0;
  std::uint64_t ticks = 0;
  double device_time_s = 0.0;  // first to last deadline (+ one period): the device's own clock
  double wall_time_s = 0.0;
  double nominal_rate_hz = 1000.0;
  ServoCounters servo;
  MissedTickMode missed_mode = MissedTickMode::RideThrough;
  MissedTickCounters missed_policy;
  SafetyCounters safety;
  std::uint64_t passivity_active_ticks = 0;
  double passivity_dissipated_j = 0.0;
  RealtimeReport realtime;
  ProcessMemory memory;
  std::size_t texture_bytes = 0;
  PublisherCounters publisher;
  std::uint64_t client_forces_accepted = 0;  // client_force_t messages the receiver took
  std::uint64_t snapshots_dropped = 0;
  std::string flight_dir;  // --flight-dir
  std::string last_flight_dump;
  // A scene with several devices: each one, in order (the fields above are then device 0's, and
  // the tick compute and wake latency the whole group's). Empty for one device.
  std::vector<DeviceSummary> devices;
};

// The servo's part of a summary: its ticks and counters, its missed-tick policy's, the safety
// stage's and the passivity controller's, and the rig's wiring (crease, passivity, stiffness: the
// first scene's).
void addServoSummary(RunSummary& s, const ServoRig& rig);
DeviceSummary deviceSummary(const std::string& name, const ServoRig& rig);

// Throws std::runtime_error if the file cannot be written.
void writeStatsJson(const std::string& path, const RunSummary& s, const LatencyHistogram& compute,
                    const LatencyHistogram& wake);
void printSummary(std::FILE* out, const RunSummary& s, const LatencyHistogram& compute, const LatencyHistogram& wake);

}  // namespace thx::srv
