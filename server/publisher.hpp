#pragma once
// The publisher thread: everything that leaves hapticd over LCM, and the flight-record dumps.
// It drains the servo's tick ring (the servo never waits for it), encodes device and contact
// state, publishes them, publishes servo statistics once per second, and writes frozen flight
// records to files. Per-client subscriptions and rates arrive with issue 5; until then it
// broadcasts on THX_DEVICE_STATE, THX_CONTACT and THX_SERVO_STATS at `publish_hz`.
#include <atomic>
#include <cstdint>
#include <string>
#include <thread>

#include "server/flight_recorder.hpp"
#include "server/servo.hpp"
#include "server/spsc_ring.hpp"
#include "server/tick_record.hpp"

namespace lcm {
class LCM;
}

namespace thx::srv {

struct PublisherOptions {
  double publish_hz = 1000.0;   // device and contact state; <= the servo rate
  double servo_rate_hz = 1000.0;
  std::string flight_dir = ".";
  bool simulated_device = false;
};

struct PublisherCounters {
  std::uint64_t records = 0;
  std::uint64_t published = 0;
  std::uint64_t publish_errors = 0;
  std::uint64_t flight_dumps = 0;
};

class Publisher {
 public:
  // lcm may be null (no transport): records are still drained and flight records still dumped.
  Publisher(SpscRing<TickRecord>& ring, const Servo& servo, FlightRecorder& recorder, lcm::LCM* lcm,
            const PublisherOptions& options);
  ~Publisher();

  void start();
  void stop();  // drains what is left, then joins

  PublisherCounters counters() const;
  std::string lastFlightDump() const;

 private:
  void run();
  void publishRecord(const TickRecord& r);
  void publishStats(std::int64_t now_ns);
  void dumpFlight();

  SpscRing<TickRecord>& ring_;
  const Servo& servo_;
  FlightRecorder& recorder_;
  lcm::LCM* lcm_;
  PublisherOptions options_;
  std::thread thread_;
  std::atomic<bool> stop_{false};
  std::int64_t decimation_ = 1;
  std::int64_t last_stats_ns_ = 0;
  std::uint64_t ticks_seen_ = 0;   // counted from the records: the servo's own counters are
  std::uint64_t missed_seen_ = 0;  // not shared across threads
  std::uint64_t last_stats_ticks_ = 0;
  std::uint64_t last_stats_missed_ = 0;
  double window_max_force_n_ = 0.0;
  std::atomic<std::uint64_t> records_{0}, published_{0}, publish_errors_{0}, flight_dumps_{0};
  mutable std::atomic<bool> dump_lock_{false};
  std::string last_dump_;
};

}  // namespace thx::srv
