#pragma once
// probe-client's command line.
#include <string>
#include <vector>

#include "base/error.hpp"
#include "thx_msgs/protocol.hpp"

namespace thx::client {

struct ProbeOptions {
  thx_msgs::Stream stream = thx_msgs::Stream::DeviceState;  // --stream NAME (required)
  double rate_hz = 0.0;
  double duration_s = 0.0;
  std::string json;
  bool batch = false;
  std::string lcm_url = thx_msgs::kDefaultLcmUrl;
  std::string client_id;            // default: probe-<pid>
  double connect_timeout_s = 10.0;  // until the subscription is granted and data flows
  bool quiet = false;
  bool help = false;  // -h / --help: print kProbeHelp
};

extern const char* const kProbeHelp;

// Parses the arguments after the program name; throws thx::UsageError naming the option.
ProbeOptions parseProbeOptions(const std::vector<std::string>& args);

}  // namespace thx::client
