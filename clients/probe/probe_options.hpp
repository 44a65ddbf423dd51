#pragma once
// probe-client's command line.
#include <string>

namespace thx::client {

struct ProbeOptions {
  std::string stream;
  double rate_hz = 0.0;
  double duration_s = 0.0;
  std::string json;
  bool batch = false;
  std::string lcm_url = "udpm://239.255.76.67:7667?ttl=0";
  std::string client_id;            // default: probe-<pid>
  double connect_timeout_s = 10.0;  // until the subscription is granted and data flows
  bool quiet = false;
};

extern const char* const kProbeHelp;

// Parses argv. On --help prints the help and exits 0; on a bad command line prints
// "probe-client: <what>" and exits 2.
ProbeOptions parseProbeOptions(int argc, char** argv);

}  // namespace thx::client
