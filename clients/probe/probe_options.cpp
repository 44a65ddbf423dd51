#include "probe_options.hpp"

#include <unistd.h>

#include <optional>

#include <thx_msgs/protocol.hpp>

#include "base/cli_number.hpp"

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
  --lcm-url URL         LCM transport (default )" THX_DEFAULT_LCM_URL R"()
  --client-id ID        1-32 of [A-Za-z0-9_-] (default probe-<pid>)
  --connect-timeout S   give up when no data has arrived after S seconds (default 10)
  --quiet               no summary on stdout
  -h, --help            this text

Exit status: 0 data received, 1 refused / nothing received / LCM unavailable, 2 bad command line.
)";

ProbeOptions parseProbeOptions(const std::vector<std::string>& args) {
  using cli::parseNumber;
  ProbeOptions o;
  std::string stream;
  bool have_rate = false, have_duration = false;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    auto value = [&]() -> const std::string& {
      if (i + 1 >= args.size()) throw UsageError(a + " needs a value");
      return args[++i];
    };
    if (a == "-h" || a == "--help") {
      o.help = true;
      return o;
    } else if (a == "--stream") {
      stream = value();
    } else if (a == "--rate") {
      o.rate_hz = parseNumber(a, value(), {0, 1e6, true, "Hz"});
      have_rate = true;
    } else if (a == "--duration") {
      o.duration_s = parseNumber(a, value(), {0, 1e6, true, "s"});
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
      o.connect_timeout_s = parseNumber(a, value(), {0, 3600, true, "s"});
    } else if (a == "--quiet") {
      o.quiet = true;
    } else {
      throw UsageError("unknown argument '" + a + "'");
    }
  }
  if (stream.empty()) throw UsageError("--stream NAME is required");
  const std::optional<thx_msgs::Stream> parsed = thx_msgs::parse_stream(stream);
  if (!parsed) throw UsageError("--stream: expected " + std::string(thx_msgs::kStreamNames) + ", got '" + stream + "'");
  o.stream = *parsed;
  if (o.batch && !thx_msgs::stream_supports_batch(o.stream)) throw UsageError("--batch works with --stream CONTACT only");
  if (!have_rate) throw UsageError("--rate HZ is required");
  if (!have_duration) throw UsageError("--duration S is required");
  if (o.json.empty()) throw UsageError("--json FILE is required");
  if (o.client_id.empty()) o.client_id = "probe-" + std::to_string(::getpid());
  if (!thx_msgs::is_valid_client_id(o.client_id))
    throw UsageError("--client-id: expected 1-32 characters of [A-Za-z0-9_-], got '" + o.client_id + "'");
  return o;
}

}  // namespace thx::client
