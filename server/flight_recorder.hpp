#pragma once
// Flight recorder: the last second of ticks, kept by the servo at no cost, dumped to a file by
// another thread when something goes wrong (docs/design.md §4 rule 2; libfranka keeps 50 records).
//
// Two preallocated buffers. The servo writes into the active one (a copy per tick of the fields
// the dump writes: FlightRecord, a quarter of a TickRecord, so the two buffers stay small enough
// for hapticd's memory goal, docs/benchmarks.md). On a fault
// it swaps in the spare buffer in O(1) and marks the full one frozen with the fault's reason;
// a non-real-time thread later writes the frozen buffer out (dumpPending) and frees it. A fault
// that arrives while a dump is still pending is counted but not frozen (the first one explains
// the most).
#include <atomic>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "server/tick_record.hpp"

namespace thx::srv {

class FlightRecorder {
 public:
  // What dumpPending writes of a tick, at the TickRecord's own precision.
  struct FlightRecord {
    std::int64_t tick = 0;
    std::int64_t wake_latency_ns = 0;
    std::int64_t compute_ns = 0;
    std::int32_t missed = 0;
    bool valid = true;
    bool in_contact = false;
    bool recovering = false;
    std::int8_t num_planes = 0;
    double p_world[3] = {};
    double v_world[3] = {};
    double depth_m = 0.0;
    double f_render[3] = {};
    double f_client[3] = {};
    double f_passive[3] = {};
    double f_out[3] = {};
    double pc_energy_j = 0.0;
    double pc_damping_ns_per_m = 0.0;
    std::uint32_t safety_flags = 0;
    std::uint32_t faults = 0;
  };

  explicit FlightRecorder(std::size_t capacity = 1000);

  // Servo thread (real-time safe).
  void record(const TickRecord& r);
  void freeze(std::uint32_t fault_bits, std::int64_t tick);

  // Any other thread. Writes the frozen buffer as CSV into `directory` (one file per fault) and
  // returns its path; empty when nothing is pending. Throws std::runtime_error on I/O errors.
  // The file is flight-tick<T>-<fault>.csv, or flight-<tag>-tick<T>-<fault>.csv with a `tag` (the
  // device's name when a server runs several: two devices may fault at one tick).
  std::string dumpPending(const std::string& directory, const std::string& tag = "");
  // Any other thread: the tick of the pending flight's fault (none pending: nullopt), and
  // dropping it unwritten (server/flight_dump_limits.hpp) so the next fault can be frozen.
  std::optional<std::int64_t> pendingTick() const;
  void discardPending();

  std::uint64_t faultsSeen() const { return faults_.load(std::memory_order_relaxed); }
  std::uint64_t faultsNotFrozen() const { return not_frozen_.load(std::memory_order_relaxed); }

 private:
  static FlightRecord slim(const TickRecord& r);

  struct Buffer {
    std::unique_ptr<FlightRecord[]> records;
    std::size_t next = 0;    // where the next record goes
    std::size_t filled = 0;  // how many are valid
  };
  std::size_t capacity_;
  Buffer buffers_[2];
  int active_ = 0;
  std::atomic<bool> frozen_{false};  // buffers_[1 - active_] holds an undumped flight
  std::uint32_t frozen_fault_ = 0;
  std::int64_t frozen_tick_ = 0;
  std::atomic<std::uint64_t> faults_{0};
  std::atomic<std::uint64_t> not_frozen_{0};
};

// Human-readable names of TickFault bits, e.g. "missed-ticks+invalid-reading".
std::string faultName(std::uint32_t fault_bits);

}  // namespace thx::srv
