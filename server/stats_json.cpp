#include "server/stats_json.hpp"
#include "base/error.hpp"
#include "base/json_text.hpp"

#include <stdexcept>

namespace thx::srv {

namespace {

std::string quantiles(const LatencyHistogram& h) {
  char buf[256];
  std::snprintf(buf, sizeof buf, "{\"p50\": %.3f, \"p99\": %.3f, \"p999\": %.3f, \"max\": %.3f, \"count\": %llu}",
                h.quantileUs(0.5), h.quantileUs(0.99), h.quantileUs(0.999), double(h.maxNs()) / 1e3,
                (unsigned long long)h.count());
  return buf;
}

// Of every device period from the first engagement to the shutdown request, missed ones included.
double fullForcePercent(const ServoCounters& c) {
  const std::uint64_t periods = c.service_ticks + c.service_missed_ticks;
  return periods > 0 ? 100.0 * double(c.full_force_ticks) / double(periods) : 0.0;
}

double achievedRate(const RunSummary& s) { return s.device_time_s > 0 ? double(s.ticks) / s.device_time_s : 0.0; }

}  // namespace

void writeStatsJson(const std::string& path, const RunSummary& s, const LatencyHistogram& compute,
                    const LatencyHistogram& wake) {
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (!f) throw thx::Error(thx::Error::Kind::Io, "cannot write statistics to " + path);
  std::fprintf(f, "{\n");
  std::fprintf(f, "  \"scene\": \"%s\",\n", json::escaped(s.scene).c_str());
  std::fprintf(f, "  \"mode\": \"%s\",\n", s.lockstep ? "lockstep" : "realtime");
  std::fprintf(f, "  \"crease_handling\": %s,\n  \"passivity_control\": %s,\n", s.crease ? "true" : "false",
               s.passivity ? "true" : "false");
  std::fprintf(f, "  \"pen_tool\": \"%s\",\n", json::escaped(s.tool).c_str());
  std::fprintf(f, "  \"stiffness_n_per_m\": %.6g,\n", s.stiffness_n_per_m);
  std::fprintf(f, "  \"ticks\": %llu,\n", (unsigned long long)s.ticks);
  std::fprintf(f, "  \"rate_hz\": %.3f,\n", achievedRate(s));
  std::fprintf(f, "  \"nominal_rate_hz\": %.3f,\n", s.nominal_rate_hz);
  std::fprintf(f, "  \"device_time_s\": %.6f,\n  \"wall_time_s\": %.6f,\n", s.device_time_s, s.wall_time_s);
  std::fprintf(f, "  \"missed_ticks\": %llu,\n", (unsigned long long)s.servo.missed_ticks);
  std::fprintf(f,
               "  \"missed_policy\": {\"policy\": \"%s\", \"ride_throughs\": %llu, \"long_stalls\": %llu, "
               "\"jumps\": %llu, \"success_rate\": %llu, \"disengaged_ticks\": %llu},\n",
               missedTickModeName(s.missed_mode), (unsigned long long)s.missed_policy.ride_throughs,
               (unsigned long long)s.missed_policy.long_stalls, (unsigned long long)s.missed_policy.jumps,
               (unsigned long long)s.missed_policy.success_rate, (unsigned long long)s.missed_policy.disengaged_ticks);
  std::fprintf(f,
               "  \"full_force\": {\"ticks\": %llu, \"contact_ticks\": %llu, \"service_ticks\": %llu, "
               "\"service_missed_ticks\": %llu, \"service_contact_ticks\": %llu},\n",
               (unsigned long long)s.servo.full_force_ticks, (unsigned long long)s.servo.contact_full_force_ticks,
               (unsigned long long)s.servo.service_ticks, (unsigned long long)s.servo.service_missed_ticks,
               (unsigned long long)s.servo.service_contact_ticks);
  std::fprintf(f, "  \"max_force_n\": %.6f,\n", s.servo.max_force_n);
  std::fprintf(f, "  \"tick_compute_us\": %s,\n", quantiles(compute).c_str());
  std::fprintf(f, "  \"wake_latency_us\": %s,\n", quantiles(wake).c_str());
  std::fprintf(f, "  \"rss_bytes\": %lld,\n  \"locked_bytes\": %lld,\n  \"texture_bytes\": %zu,\n",
               (long long)s.memory.rss_bytes, (long long)s.memory.locked_bytes, s.texture_bytes);
  std::fprintf(f, "  \"client_forces_accepted\": %llu,\n", (unsigned long long)s.client_forces_accepted);
  std::fprintf(f, "  \"contact_ticks\": %llu,\n  \"client_force_ticks\": %llu,\n  \"faults\": %llu,\n  \"invalid_readings\": %llu,\n",
               (unsigned long long)s.servo.contact_ticks, (unsigned long long)s.servo.client_force_ticks,
               (unsigned long long)s.servo.faults,
               (unsigned long long)s.servo.invalid_readings);
  std::fprintf(f,
               "  \"safety\": {\"peak_clamped\": %llu, \"continuous_limited\": %llu, \"rate_limited\": %llu, "
               "\"disengage_events\": %llu, \"engaging_ticks\": %llu},\n",
               (unsigned long long)s.safety.peak_clamped, (unsigned long long)s.safety.continuous_limited,
               (unsigned long long)s.safety.rate_limited, (unsigned long long)s.safety.disengage_events,
               (unsigned long long)s.safety.engaging);
  std::fprintf(f, "  \"passivity\": {\"active_ticks\": %llu, \"dissipated_j\": %.6g},\n",
               (unsigned long long)s.passivity_active_ticks, s.passivity_dissipated_j);
  std::fprintf(f, "  \"realtime\": {\"sched_fifo\": %s, \"memory_locked\": %s, \"pinned\": %s},\n",
               s.realtime.fifo ? "true" : "false", s.realtime.memory_locked ? "true" : "false",
               s.realtime.pinned ? "true" : "false");
  std::fprintf(f, "  \"published_messages\": %llu,\n  \"publish_errors\": %llu,\n  \"snapshots_dropped\": %llu,\n",
               (unsigned long long)s.publisher.published, (unsigned long long)s.publisher.publish_errors,
               (unsigned long long)s.snapshots_dropped);
  std::fprintf(f, "  \"publisher_fifo\": %s,\n  \"data_ports_open\": %d,\n", s.publisher.fifo ? "true" : "false",
               s.publisher.data_ports_open);
  std::fprintf(f, "  \"flight_dir\": \"%s\",\n  \"flight_dumps\": %llu,\n", json::escaped(s.flight_dir).c_str(),
               (unsigned long long)s.publisher.flight_dumps);
  std::fprintf(f, "  \"flight_dumps_over_count\": %llu,\n  \"flight_dumps_over_rate\": %llu,\n",
               (unsigned long long)s.publisher.flight_dumps_over_count,
               (unsigned long long)s.publisher.flight_dumps_over_rate);
  std::fprintf(f, "  \"last_flight_dump\": \"%s\"", json::escaped(s.last_flight_dump).c_str());
  if (!s.devices.empty()) {
    std::fprintf(f, ",\n  \"devices\": [\n");
    for (std::size_t i = 0; i < s.devices.size(); ++i) {
      const DeviceSummary& d = s.devices[i];
      std::fprintf(f,
                   "    {\"name\": \"%s\", \"contact_ticks\": %llu, \"max_force_n\": %.6f, \"faults\": %llu, "
                   "\"invalid_readings\": %llu, \"full_force_percent\": %.3f, \"disengaged_ticks\": %llu, "
                   "\"peak_clamped\": %llu, \"passivity_active_ticks\": %llu, \"compute_p99_us\": %.3f}%s\n",
                   json::escaped(d.name).c_str(), (unsigned long long)d.servo.contact_ticks, d.servo.max_force_n,
                   (unsigned long long)d.servo.faults, (unsigned long long)d.servo.invalid_readings,
                   fullForcePercent(d.servo), (unsigned long long)d.missed_policy.disengaged_ticks,
                   (unsigned long long)d.safety.peak_clamped, (unsigned long long)d.passivity_active_ticks,
                   d.compute_p99_us, i + 1 < s.devices.size() ? "," : "");
    }
    std::fprintf(f, "  ]");
  }
  std::fprintf(f, "\n}\n");
  if (std::fclose(f) != 0) throw thx::Error(thx::Error::Kind::Io, "cannot write statistics to " + path);
}

void printSummary(std::FILE* out, const RunSummary& s, const LatencyHistogram& compute,
                  const LatencyHistogram& wake) {
  std::fprintf(out, "hapticd summary (%s, %s)\n", s.scene.c_str(), s.lockstep ? "lock-step" : "real time");
  std::fprintf(out, "  ticks            %llu in %.3f s of device time (%.1f Hz; %.3f s wall)\n",
               (unsigned long long)s.ticks, s.device_time_s, achievedRate(s), s.wall_time_s);
  if (s.devices.empty()) {
    std::fprintf(out, "  missed ticks     %llu; faults %llu\n", (unsigned long long)s.servo.missed_ticks,
                 (unsigned long long)s.servo.faults);
  } else {
    std::uint64_t faults = 0;
    for (const DeviceSummary& d : s.devices) faults += d.servo.faults;
    std::fprintf(out, "  missed ticks     %llu; faults %llu over the %zu devices\n",
                 (unsigned long long)s.servo.missed_ticks, (unsigned long long)faults, s.devices.size());
  }
  const MissedTickCounters& m = s.missed_policy;
  std::fprintf(out,
               "  gaps (%s)  %llu ridden through; disengaged for %llu long stalls, %llu jumps, %llu success-rate "
               "drops; full force %.2f %% of device periods since engaged\n",
               missedTickModeName(s.missed_mode), (unsigned long long)m.ride_throughs,
               (unsigned long long)m.long_stalls, (unsigned long long)m.jumps, (unsigned long long)m.success_rate,
               fullForcePercent(s.servo));
  std::fprintf(out, "  tick compute     p50 %.1f us, p99 %.1f us, max %.1f us\n", compute.quantileUs(0.5),
               compute.quantileUs(0.99), double(compute.maxNs()) / 1e3);
  if (!s.lockstep) {
    std::fprintf(out, "  wake latency     p50 %.1f us, p99 %.1f us, max %.1f us\n", wake.quantileUs(0.5),
                 wake.quantileUs(0.99), double(wake.maxNs()) / 1e3);
  }
  for (const DeviceSummary& d : s.devices) {
    std::fprintf(out,
                 "  device %-9s contact %llu ticks; max force %.3f N; faults %llu; full force %.2f %%; peak-clamped "
                 "%llu; passivity active %llu ticks; its compute p99 %.1f us\n",
                 d.name.c_str(), (unsigned long long)d.servo.contact_ticks, d.servo.max_force_n,
                 (unsigned long long)d.servo.faults, fullForcePercent(d.servo), (unsigned long long)d.safety.peak_clamped,
                 (unsigned long long)d.passivity_active_ticks, d.compute_p99_us);
  }
  if (!s.devices.empty()) std::fprintf(out, "  device 0's details:\n");
  // A capsule meets creases with its own contacts: the point renderer's crease handling is not its.
  const std::string pen = s.tool == "point" ? std::string("crease ") + (s.crease ? "on" : "off") : s.tool + " tool";
  std::fprintf(out, "  contact          %llu ticks; max force %.3f N (stiffness %.0f N/m, %s, passivity %s)\n",
               (unsigned long long)s.servo.contact_ticks, s.servo.max_force_n, s.stiffness_n_per_m, pen.c_str(),
               s.passivity ? "on" : "off");
  std::fprintf(out, "  safety           peak-clamped %llu, rate-limited %llu, continuous-limited %llu ticks\n",
               (unsigned long long)s.safety.peak_clamped, (unsigned long long)s.safety.rate_limited,
               (unsigned long long)s.safety.continuous_limited);
  std::fprintf(out, "  passivity ctrl   active %llu ticks, dissipated %.3g J\n",
               (unsigned long long)s.passivity_active_ticks, s.passivity_dissipated_j);
  std::fprintf(out, "  memory           %.1f MB resident, %.1f MB locked (texture %.1f MB)\n",
               double(s.memory.rss_bytes) / 1e6, double(s.memory.locked_bytes) / 1e6, double(s.texture_bytes) / 1e6);
  std::fprintf(out, "  real time        SCHED_FIFO %s, mlockall %s\n", s.realtime.fifo ? "yes" : "no",
               s.realtime.memory_locked ? "yes" : "no");
  std::fprintf(out, "  published        %llu LCM messages (%llu errors)\n", (unsigned long long)s.publisher.published,
               (unsigned long long)s.publisher.publish_errors);
  const std::uint64_t unwritten = s.publisher.flight_dumps_over_count + s.publisher.flight_dumps_over_rate;
  if (s.publisher.flight_dumps > 0 || unwritten > 0) {
    std::fprintf(out, "  flight records   %llu written to %s; %llu faults not written (%llu over --flight-max, %llu "
                 "within --flight-interval)\n",
                 (unsigned long long)s.publisher.flight_dumps, s.flight_dir.c_str(), (unsigned long long)unwritten,
                 (unsigned long long)s.publisher.flight_dumps_over_count,
                 (unsigned long long)s.publisher.flight_dumps_over_rate);
  }
}

DeviceSummary deviceSummary(const std::string& name, const ServoRig& rig) {
  DeviceSummary d;
  d.name = name;
  d.servo = rig.servo().counters();
  d.missed_policy = rig.servo().missedTickPolicy().counters();
  d.safety = rig.safety().counters();
  d.passivity_active_ticks = rig.passivity().activeTicks();
  d.compute_p99_us = rig.servo().computeHistogram().quantileUs(0.99);
  return d;
}

void addServoSummary(RunSummary& s, const ServoRig& rig) {
  const Servo& servo = rig.servo();
  s.ticks = servo.counters().ticks;
  s.servo = servo.counters();
  s.missed_policy = servo.missedTickPolicy().counters();
  s.missed_mode = rig.config().missed_mode;
  s.safety = rig.safety().counters();
  s.passivity_active_ticks = rig.passivity().activeTicks();
  s.passivity_dissipated_j = rig.passivity().dissipatedEnergy();
  s.crease = rig.config().renderer.crease_handling;
  if (const CapsuleTool* tool = servo.capsuleTool()) {
    char text[64];
    std::snprintf(text, sizeof text, "capsule %g x %g mm", tool->config().length_m * 1e3, tool->config().radius_m * 1e3);
    s.tool = text;
  }
  s.passivity = rig.config().passivity;
  s.stiffness_n_per_m = rig.config().renderer.stiffness_n_per_m;
}

}  // namespace thx::srv
