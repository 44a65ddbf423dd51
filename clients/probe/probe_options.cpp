#include "probe_options.hpp"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <thx_msgs/protocol.hpp>

namespace thx::client {

const char* const kProbeHelp = R"(usage: probe-client --stream NAME --rate HZ --duration S --json FILE [options]

Subscribes to one hapticd stream at a rate, receives it for a while, and reports what arrived:
messages, achieved rate, latency from the server's tick time to receipt (p50/p99/max), gaps and
duplicates. Latency is meaningful when probe and server share a host (CLOCK_MONOTONIC) and the
server runs in real time (not --lockstep).

  --stream NAME         DEVICE_STATE, CONTACT or SERVO_STATS
  --rate HZ             requested rate (messages per second; with --batch, batches per second)
  --duration S          how long to receive, counted from the first message
  --json FILE           write the report as JSON ('-' for stdout)
  --batch               CONTACT only: every tick's sample, batched (contact_batch_t)
  --lcm-url URL         LCM transport (default udpm://239.255.76.67:7667?ttl=0)
  --client-id ID        1-32 of [A-Za-z0-9_-] (default probe-<pid>)
  --connect-timeout S   give up when no data has arrived after S seconds (default 10)
  --quiet               no summary on stdout
  -h, --help            this text

Exit status: 0 data received, 1 refused / nothing received / LCM unavailable, 2 bad command line.
)";

namespace {
[[noreturn]] void usage(const std::string& message) {
  std::fprintf(stderr, "probe-client: %s (see probe-client --help)\n", message.c_str());
  std::exit(2);
}

double number(const std::string& option, const char* text) {
  char* end = nullptr;
  const double v = std::strtod(text, &end);
  if (!end || end == text || *end != '\0' || !std::isfinite(v)) usage(option + " expects a number, got '" + text + "'");
  return v;
}
}  // namespace

ProbeOptions parseProbeOptions(int argc, char** argv) {
  ProbeOptions o;
  bool have_rate = false, have_duration = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> const char* {
      if (i + 1 >= argc) usage(a + " needs a value");
      return argv[++i];
    };
    if (a == "-h" || a == "--help") {
      std::fputs(kProbeHelp, stdout);
      std::exit(0);
    } else if (a == "--stream") {
      o.stream = value();
    } else if (a == "--rate") {
      o.rate_hz = number(a, value());
      have_rate = true;
    } else if (a == "--duration") {
      o.duration_s = number(a, value());
      have_duration = true;
    } else if (a == "--json") {
      o.json = value();
    } else if (a == "--batch") {
      o.batch = true;
    } else if (a == "--lcm-url") {
      o.lcm_url = value();
    } else if (a == "--client-id") {
      o.client_id = value();
    } else if (a == "--connect-timeout") {
      o.connect_timeout_s = number(a, value());
    } else if (a == "--quiet") {
      o.quiet = true;
    } else {
      usage("unknown argument '" + a + "'");
    }
  }
  if (o.stream.empty()) usage("--stream NAME is required");
  if (!thx_msgs::is_known_stream(o.stream)) {
    usage("--stream: expected DEVICE_STATE, CONTACT or SERVO_STATS, got '" + o.stream + "'");
  }
  if (o.batch && !thx_msgs::stream_supports_batch(o.stream)) usage("--batch works with --stream CONTACT only");
  if (!have_rate) usage("--rate HZ is required");
  if (o.rate_hz <= 0) usage("--rate must be > 0");
  if (!have_duration) usage("--duration S is required");
  if (o.duration_s <= 0) usage("--duration must be > 0");
  if (o.json.empty()) usage("--json FILE is required");
  if (o.connect_timeout_s <= 0) usage("--connect-timeout must be > 0");
  if (o.client_id.empty()) o.client_id = "probe-" + std::to_string(::getpid());
  if (!thx_msgs::is_valid_client_id(o.client_id)) {
    usage("--client-id: expected 1-32 characters of [A-Za-z0-9_-], got '" + o.client_id + "'");
  }
  return o;
}

}  // namespace thx::client
