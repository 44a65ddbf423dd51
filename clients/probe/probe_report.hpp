#pragma once
// probe-client's report: JSON file and a short summary.
#include <cstdio>
#include <string>

#include "probe_options.hpp"
#include "thx_client/client.hpp"
#include "thx_client/stream_monitor.hpp"

namespace thx::client {

struct ProbeResult {
  ProbeOptions options;
  StreamStatus status;          // as granted (or refused)
  StreamReport report;
  std::int64_t server_instance = 0;
  std::uint64_t reconnects = 0;
  // Timing of the handshake, from the first subscribe() (CLOCK_MONOTONIC), in seconds; < 0: never.
  double admission_s = -1.0;      // until the first answer (granted or refused)
  double first_message_s = -1.0;  // until the first message of the stream
  // This process's CPU time (user + system, getrusage) over the receiving window (first message
  // to end) and over the whole run, in seconds; the window's wall time.
  double cpu_window_s = 0.0, cpu_total_s = 0.0, window_wall_s = 0.0;
  std::string error;            // why the probe failed, "" when data arrived
};

// Throws std::runtime_error naming the file when it cannot be written.
void writeProbeJson(const std::string& path, const ProbeResult& r);
void printProbeSummary(std::FILE* out, const ProbeResult& r);

}  // namespace thx::client
