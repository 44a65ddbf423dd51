// probe-client: subscribes to one hapticd stream and reports how it arrives (docs/clients.md).
// `probe-client --help` for options.
#include <sys/resource.h>

#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "base/program_main.hpp"
#include "probe_options.hpp"
#include "probe_report.hpp"
#include "thx_client/app.hpp"
#include "thx_client/stream_monitor.hpp"

namespace {

using namespace thx::client;

// user + system CPU time of this process, in seconds.
double cpuSeconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + 1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

// Receives until the stream is refused, no data came within the connect timeout, the duration
// since the first message has passed, or a stop signal arrives.
void receive(const ProbeOptions& o, ProbeResult& result) {
  ClientApp app(o.client_id, o.lcm_url, o.connect_timeout_s);
  Client& client = app.client();
  std::optional<StreamMonitor> monitor;
  std::int64_t first_ns = 0, instance = 0, asked_ns = 0;
  double first_cpu = 0.0;
  auto seen = [&](std::int64_t now) {
    if (first_ns == 0) {
      first_ns = now;
      first_cpu = cpuSeconds();
      result.first_message_s = 1e-9 * double(now - asked_ns);
    }
    if (!monitor) return false;
    // Ticks restart with the server: compare nothing across a restart.
    if (instance != 0 && client.serverInstance() != instance) monitor->serverRestarted();
    instance = client.serverInstance();
    return true;
  };
  client.onStatus([&](const StreamStatus& s) {
    if (s.state != SubscriptionState::Pending && result.admission_s < 0)
      result.admission_s = 1e-9 * double(monotonicNs() - asked_ns);
    if (s.state == SubscriptionState::Active && !monitor) monitor.emplace(s.granted_hz);
  });
  client.onDeviceState([&](const thx_msgs::device_state_t& m, std::int64_t now) {
    if (seen(now)) monitor->onMessage(m.tick, m.utime, now, m.device);
  });
  client.onContact([&](const thx_msgs::contact_t& m, std::int64_t now) {
    if (seen(now)) monitor->onMessage(m.tick, m.utime, now, m.device);
  });
  client.onContactBatch([&](const thx_msgs::contact_batch_t& m, std::int64_t now) {
    if (seen(now)) monitor->onBatch(m, now);
  });
  // SERVO_STATS has no tick: its tick count orders it.
  client.onServoStats([&](const thx_msgs::servo_stats_t& m, std::int64_t now) {
    if (seen(now)) monitor->onMessage(m.ticks, m.utime, now, m.device);
  });
  asked_ns = monotonicNs();
  client.subscribe(o.stream, o.rate_hz, o.batch);

  auto refused = [&] {
    const auto st = client.status(o.stream);
    return st && st->state == SubscriptionState::Refused;
  };
  if (app.pollUntil([&] { return first_ns != 0 || refused(); }, o.connect_timeout_s) && !refused())
    app.pollUntil([&] { return refused() || monotonicNs() - first_ns >= std::int64_t(o.duration_s * 1e9); }, 1e9);

  if (first_ns != 0) {
    result.cpu_window_s = cpuSeconds() - first_cpu;
    result.window_wall_s = 1e-9 * double(monotonicNs() - first_ns);
  }
  result.cpu_total_s = cpuSeconds();
  if (auto st = client.status(o.stream)) result.status = *st;
  if (monitor) result.report = monitor->report();
  result.server_instance = client.serverInstance();
  result.reconnects = client.counters().reconnects;
}

ProbeResult probe(const ProbeOptions& o) {
  ProbeResult result;
  result.options = o;
  result.status.stream = o.stream;
  result.status.batch = o.batch;
  result.status.requested_hz = o.rate_hz;
  try {
    receive(o, result);
  } catch (const thx::Error& e) {  // no LCM: still a report that says so
    result.error = e.what();
    return result;
  }
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
  return thx::runProgram("probe-client", kProbeHelp, argc, argv, [](const std::vector<std::string>& args) {
    const ProbeOptions o = parseProbeOptions(args);
    const ProbeResult r = probe(o);
    writeProbeJson(o.json, r);
    if (!o.quiet && o.json != "-") printProbeSummary(stdout, r);
    if (!r.error.empty()) {
      std::fprintf(stderr, "probe-client: %s\n", r.error.c_str());
      return 1;
    }
    return 0;
  });
}
