#pragma once
// Delivery statistics of one stream as a client sees it: messages, achieved rate, latency from
// the server's tick time to receipt, gaps and duplicates (probe-client's report, docs/clients.md).
//
// Latency compares the server's utime (CLOCK_MONOTONIC µs at the tick) with the receipt time on
// the client's CLOCK_MONOTONIC: meaningful on the same host only, and not in lock-step runs.
// Gaps: latest-value streams carry no sequence number, so a gap is an interval between two
// messages' server times longer than 1.5 periods of the granted rate (the server's intervals
// are whole ticks, within one tick of the period); batches are checked exactly by seq and
// next_tick.
// Devices (protocol 6): a server with several sends each device's messages at the granted rate on
// one channel, all on the one servo clock's ticks, each device counting its own batch seq, so a
// message is compared with the previous one of its own device only. The rates and latencies are
// over every message fed in (a kit Client's callbacks feed one device's, the one it follows).
#include <array>
#include <cstdint>
#include <vector>

#include <thx_msgs/contact_batch_t.hpp>

#include "thx_client/devices.hpp"

namespace thx::client {

// One device's share of a StreamReport's counts.
struct DeviceCounts {
  std::uint64_t messages = 0, duplicates = 0, gaps = 0, missing = 0;
};

struct StreamReport {
  std::uint64_t messages = 0;
  std::uint64_t duplicates = 0;       // a message not newer than the previous one
  std::uint64_t gaps = 0;             // places where one or more messages were missing
  std::uint64_t missing = 0;          // messages missing in those gaps (estimated for latest-value streams)
  std::uint64_t samples = 0;          // batches: samples received
  std::uint64_t samples_missing = 0;  // batches: samples lost in transit (lost batches)
  std::uint64_t samples_dropped = 0;  // batches: samples the server dropped itself (num_dropped)
  std::uint64_t samples_out_of_order = 0;  // batches: samples whose ticks are not consecutive
  std::uint64_t restarts = 0;         // server restarts seen (sequences and ticks start again)
  double span_s = 0.0;                // first to last receipt
  double achieved_rate_hz = 0.0;      // (messages - 1) / span
  // The same over the messages received from kSettleNs after the first one on: without the
  // start-up backlog (a client started beside 63 others waits for the CPU, its first messages
  // queue in its socket and then arrive in a burst, which shortens `span` and raises the rate
  // by backlog / span). 0 when fewer than two messages came after the settling time.
  double steady_rate_hz = 0.0;
  double sample_rate_hz = 0.0;        // batches: samples after the first batch / span
  double latency_p50_us = 0.0, latency_p99_us = 0.0, latency_max_us = 0.0;
  std::array<DeviceCounts, kMaxDevices> by_device{};  // messages, duplicates, gaps by device index
  std::uint64_t outside_devices = 0;  // messages of a device index outside 0..kMaxDevices-1: counted
                                      // here only (not in messages, rates or latencies)
};

class StreamMonitor {
 public:
  static constexpr std::int64_t kSettleNs = 2'000'000'000;
  explicit StreamMonitor(double granted_rate_hz) : rate_hz_(granted_rate_hz) {}
  // A latest-value message of `device`: its tick (ordering), server time and receipt time.
  void onMessage(std::int64_t tick, std::int64_t server_utime_us, std::int64_t received_ns, int device = 0);
  // A batch (of b.device); its latency is that of its newest sample. A new server_instance is a restart.
  void onBatch(const thx_msgs::contact_batch_t& b, std::int64_t received_ns);
  // The server restarted (a new server_instance): ticks and sequences start again, so the next
  // message of each device is compared with nothing.
  void serverRestarted();
  StreamReport report() const;

 private:
  // Where one device's previous message left off.
  struct Track {
    bool any = false;  // a message since the start or the last restart
    std::int64_t last_tick = 0, last_utime_us = 0;
    std::int64_t last_seq = 0, last_next_tick = 0;
  };
  // The track of `device` (nullptr, counted in outside_devices, for an index out of range).
  Track* track(int device);
  // A duplicate (counted) when the message is not newer than its device's previous one.
  bool duplicate(bool older, int device);
  void gap(int device, std::uint64_t missing);
  void received(int device, std::int64_t server_utime_us, std::int64_t received_ns);

  double rate_hz_;
  StreamReport r_;
  std::vector<double> latencies_us_;
  std::int64_t first_ns_ = 0, last_ns_ = 0;
  std::int64_t first_steady_ns_ = 0;
  std::uint64_t steady_messages_ = 0;  // received from first_ns_ + kSettleNs on
  std::array<Track, kMaxDevices> tracks_{};
  std::int64_t last_instance_ = 0;
  std::uint64_t first_samples_ = 0;
  bool any_ = false;  // a message of any device since the start or the last restart
};

}  // namespace thx::client
