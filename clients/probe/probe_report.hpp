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
  std::string error;            // why the probe failed, "" when data arrived
};

// Throws std::runtime_error naming the file when it cannot be written.
void writeProbeJson(const std::string& path, const ProbeResult& r);
void printProbeSummary(std::FILE* out, const ProbeResult& r);

}  // namespace thx::client
