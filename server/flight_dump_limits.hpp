#pragma once
// Caps on flight-record files (issue 12): a server under foreign load can fault every few
// seconds, and one file per fault left thousands of files in an hour. A dump is admitted only
// while fewer than `max_files` were written and at least `min_interval_s` of device time has
// passed since the fault of the last written one; a refused flight is dropped from the recorder
// at once (so the next fault can be frozen) and counted by reason.
//
// Device time (the fault's tick × the servo period), not the wall clock: the same run admits the
// same dumps, in lock-step as in real time. Non-real-time (the publisher thread).
#include <cstdint>
#include <string>

#include "server/flight_recorder.hpp"

namespace thx::srv {

struct FlightDumpLimits {
  std::uint64_t max_files = 20;  // per run; 0 = write none
  double min_interval_s = 10.0;  // device time between the faults of two written files
};

enum class FlightDumpOutcome { Nothing, Written, OverCount, OverRate };

class FlightDumpGate {
 public:
  FlightDumpGate(const FlightDumpLimits& limits, double period_s);

  // Decides for a flight frozen at `tick` and books the decision.
  FlightDumpOutcome admit(std::int64_t tick);

  std::uint64_t written() const { return written_; }
  std::uint64_t overCount() const { return over_count_; }
  std::uint64_t overRate() const { return over_rate_; }
  const FlightDumpLimits& limits() const { return limits_; }

 private:
  FlightDumpLimits limits_;
  double period_s_;
  bool any_written_ = false;
  std::int64_t last_written_tick_ = 0;
  std::uint64_t written_ = 0, over_count_ = 0, over_rate_ = 0;
};

struct FlightDump {
  FlightDumpOutcome outcome = FlightDumpOutcome::Nothing;
  std::string path;  // the file, when Written
};

// Writes the recorder's pending flight into `directory` if the gate admits it, else drops it.
// Throws what FlightRecorder::dumpPending throws. `tag`: FlightRecorder::dumpPending's.
FlightDump dumpWithinLimits(FlightRecorder& recorder, FlightDumpGate& gate, const std::string& directory,
                            const std::string& tag = "");

}  // namespace thx::srv
