// probe-client: subscribes to one hapticd stream and reports how it arrives (docs/clients.md).
// `probe-client --help` for options.
#include <csignal>
#include <cstdio>
#include <lcm/lcm-cpp.hpp>
#include <optional>
#include <stdexcept>

#include "probe_options.hpp"
#include "probe_report.hpp"
#include "thx_client/client.hpp"
#include "thx_client/stream_monitor.hpp"

namespace {

volatile std::sig_atomic_t g_stop = 0;
void onSignal(int) { g_stop = 1; }

using namespace thx::client;

ProbeResult probe(const ProbeOptions& o) {
  ProbeResult result;
  result.options = o;
  result.status.stream = o.stream;
  result.status.batch = o.batch;
  result.status.requested_hz = o.rate_hz;
  lcm::LCM lcm(o.lcm_url);
  if (!lcm.good()) {
    result.error = "LCM is not available at '" + o.lcm_url +
                   "' (no multicast route? try `ip route add 224.0.0.0/4 dev lo` as root, or --lcm-url)";
    return result;
  }
  Client client(lcm, o.client_id);
  std::optional<StreamMonitor> monitor;
  std::int64_t first_ns = 0, instance = 0;
  auto seen = [&](std::int64_t now) {
    if (first_ns == 0) first_ns = now;
    if (!monitor) return false;
    // Ticks restart with the server: compare nothing across a restart.
    if (instance != 0 && client.serverInstance() != instance) monitor->serverRestarted();
    instance = client.serverInstance();
    return true;
  };
  client.onStatus([&](const StreamStatus& s) {
    if (s.state == SubscriptionState::Active && !monitor) monitor.emplace(s.granted_hz);
  });
  client.onDeviceState([&](const thx_msgs::device_state_t& m, std::int64_t now) {
    if (seen(now)) monitor->onMessage(m.tick, m.utime, now);
  });
  client.onContact([&](const thx_msgs::contact_t& m, std::int64_t now) {
    if (seen(now)) monitor->onMessage(m.tick, m.utime, now);
  });
  client.onContactBatch([&](const thx_msgs::contact_batch_t& m, std::int64_t now) {
    if (seen(now)) monitor->onBatch(m, now);
  });
  // SERVO_STATS has no tick: its tick count orders it.
  client.onServoStats([&](const thx_msgs::servo_stats_t& m, std::int64_t now) {
    if (seen(now)) monitor->onMessage(m.ticks, m.utime, now);
  });
  client.subscribe(o.stream, o.rate_hz, o.batch);

  const std::int64_t start = monotonicNs();
  const auto connect_ns = std::int64_t(o.connect_timeout_s * 1e9);
  const auto duration_ns = std::int64_t(o.duration_s * 1e9);
  while (!g_stop) {
    const std::int64_t now = monotonicNs();
    const auto st = client.status(o.stream);
    if (st && st->state == SubscriptionState::Refused) break;
    if (first_ns == 0 && now - start > connect_ns) break;
    if (first_ns != 0 && now - first_ns >= duration_ns) break;
    if (client.poll(5) < 0) {
      result.error = "LCM receive failed";
      break;
    }
  }
  if (auto st = client.status(o.stream)) result.status = *st;
  if (monitor) result.report = monitor->report();
  result.server_instance = client.serverInstance();
  result.reconnects = client.counters().reconnects;
  if (!result.error.empty()) return result;
  if (result.status.state == SubscriptionState::Refused) {
    result.error = "refused: " + result.status.reason;
  } else if (result.report.messages == 0) {
    result.error = result.status.state == SubscriptionState::Active
                       ? "granted, but no message arrived within " + std::to_string(o.connect_timeout_s) + " s"
                       : "no reply from hapticd within " + std::to_string(o.connect_timeout_s) + " s on " + o.lcm_url;
  }
  return result;
}

}  // namespace

int main(int argc, char** argv) {
  const ProbeOptions o = parseProbeOptions(argc, argv);
  struct sigaction sa {};
  sa.sa_handler = onSignal;
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
  try {
    const ProbeResult r = probe(o);
    writeProbeJson(o.json, r);
    if (!o.quiet && o.json != "-") printProbeSummary(stdout, r);
    if (!r.error.empty()) {
      std::fprintf(stderr, "probe-client: %s\n", r.error.c_str());
      return 1;
    }
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "probe-client: %s\n", e.what());
    return 1;
  }
}
