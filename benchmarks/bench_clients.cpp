// Part 5 of docs/benchmarks.md: hapticd under client load (issue 5).
//
// 16 probe-clients (4 batched CONTACT at 1 kHz, every tick's sample; 12 DEVICE_STATE at 60 Hz)
// against a real-time hapticd for --seconds (60), over LCM udpm with ttl=0 on a port of its own.
// Reports every client's achieved rate, messages, missing, latency; and the servo's tick compute
// p99 under that load against the same hapticd with no client, run just before and just after
// (the ratio is within one benchmark run, on the same machine state). Measures, never asserts.
//
// Usage: bench_clients --hapticd PATH --probe PATH --scene FILE [--seconds S] [--baseline-seconds S]
//                      [--port N] [--workdir DIR] [--json F] [--csv F] [--md F]
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <thread>
#include <vector>

#include "benchmarks/proc_tools.hpp"

namespace {

using namespace thx;

struct Options {
  std::string hapticd, probe, scene, workdir = ".", json, csv, md;
  double seconds = 60, baseline_seconds = 30;
  int port = 7841;
};

struct ClientResult {
  std::string name, stream;
  bool batch = false;
  double rate = 0, granted = 0, messages = 0, achieved = 0, rate_error = 0, missing = 0, duplicates = 0;
  double samples = 0, samples_missing = 0, lat_p50 = 0, lat_p99 = 0, lat_max = 0;
  int exit_status = -1;
  std::string error;
};

struct ServoResult {
  std::string phase, command;
  int exit_status = -1;
  double ticks = 0, missed = 0, rate_hz = 0, p50 = 0, p99 = 0, p999 = 0, max = 0, wake_p99 = 0, max_force = 0;
  bool fifo = false;
};

[[noreturn]] void usage(const std::string& why) {
  std::fprintf(stderr,
               "bench_clients: %s\nusage: bench_clients --hapticd PATH --probe PATH --scene FILE [--seconds S] "
               "[--baseline-seconds S] [--port N] [--workdir DIR] [--json F] [--csv F] [--md F]\n",
               why.c_str());
  std::exit(2);
}

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&] {
      if (i + 1 >= argc) usage(a + " needs a value");
      return std::string(argv[++i]);
    };
    if (a == "--hapticd") o.hapticd = value();
    else if (a == "--probe") o.probe = value();
    else if (a == "--scene") o.scene = value();
    else if (a == "--seconds") o.seconds = std::atof(value().c_str());
    else if (a == "--baseline-seconds") o.baseline_seconds = std::atof(value().c_str());
    else if (a == "--port") o.port = std::atoi(value().c_str());
    else if (a == "--workdir") o.workdir = value();
    else if (a == "--json") o.json = value();
    else if (a == "--csv") o.csv = value();
    else if (a == "--md") o.md = value();
    else usage("unknown argument '" + a + "'");
  }
  if (o.hapticd.empty() || o.probe.empty() || o.scene.empty()) usage("--hapticd, --probe and --scene are required");
  if (o.seconds <= 0 || o.baseline_seconds <= 0) usage("--seconds and --baseline-seconds must be > 0");
  return o;
}

double num(const std::string& text, const std::string& object, const std::string& key) {
  return test::jsonNumber(text, object, key).value_or(NAN);
}

std::vector<std::string> hapticdArgv(const Options& o, const std::string& url, const std::string& stats,
                                     double duration) {
  char d[32];
  std::snprintf(d, sizeof d, "%g", duration);
  return {o.hapticd, "--scene", o.scene, "--duration", d, "--quiet", "--lcm-url", url, "--stats-json", stats,
          "--flight-dir", o.workdir};
}

ServoResult readServo(const std::string& phase, const std::string& command, int status, const std::string& path) {
  ServoResult r;
  r.phase = phase;
  r.command = command;
  r.exit_status = status;
  const std::string s = test::slurp(path);
  r.ticks = num(s, "", "ticks");
  r.missed = num(s, "", "missed_ticks");
  r.rate_hz = num(s, "", "rate_hz");
  r.max_force = num(s, "", "max_force_n");
  r.p50 = num(s, "tick_compute_us", "p50");
  r.p99 = num(s, "tick_compute_us", "p99");
  r.p999 = num(s, "tick_compute_us", "p999");
  r.max = num(s, "tick_compute_us", "max");
  r.wake_p99 = num(s, "wake_latency_us", "p99");
  r.fifo = test::jsonBool(s, "realtime", "sched_fifo").value_or(false);
  return r;
}

ServoResult baseline(const Options& o, const std::string& url, const std::string& phase) {
  const std::string stats = o.workdir + "/bench_clients_" + phase + ".json";
  const auto argv = hapticdArgv(o, url, stats, o.baseline_seconds);
  std::fprintf(stderr, "bench_clients: %s: hapticd alone for %g s\n", phase.c_str(), o.baseline_seconds);
  const pid_t p = bench::spawn(argv, o.workdir + "/bench_clients_" + phase + ".log");
  const int status = test::waitExit(p);
  return readServo(phase, test::commandLine(argv), status, stats);
}

std::string csvRow(const ClientResult& c) {
  char buf[512];
  std::snprintf(buf, sizeof buf, "%s,%s,%d,%g,%g,%.0f,%.4f,%.6f,%.0f,%.0f,%.0f,%.0f,%.1f,%.1f,%.1f,%d\n", c.name.c_str(),
                c.stream.c_str(), int(c.batch), c.rate, c.granted, c.messages, c.achieved, c.rate_error, c.missing,
                c.duplicates, c.samples, c.samples_missing, c.lat_p50, c.lat_p99, c.lat_max, c.exit_status);
  return buf;
}

}  // namespace

int main(int argc, char** argv) {
  const Options o = parse(argc, argv);
  const std::string url = "udpm://239.255.76.67:" + std::to_string(o.port) + "?ttl=0";
  std::vector<ServoResult> servo;
  servo.push_back(baseline(o, url, "before"));

  // The loaded run: hapticd until the probes are done.
  const std::string stats = o.workdir + "/bench_clients_load.json";
  const auto hargv = hapticdArgv(o, url, stats, 0);
  std::fprintf(stderr, "bench_clients: load: hapticd + 16 clients for %g s\n", o.seconds);
  const pid_t server = bench::spawn(hargv, o.workdir + "/bench_clients_load.log");
  std::vector<ClientResult> clients;
  std::vector<pid_t> pids;
  char dur[32];
  std::snprintf(dur, sizeof dur, "%g", o.seconds);
  for (int k = 0; k < 16; ++k) {
    ClientResult c;
    c.batch = k < 4;
    c.name = (c.batch ? "audio" : "visual") + std::to_string(k);
    c.stream = c.batch ? "CONTACT" : "DEVICE_STATE";
    c.rate = c.batch ? 1000 : 60;
    std::vector<std::string> a = {o.probe,    "--lcm-url", url,   "--client-id", c.name, "--stream", c.stream, "--rate",
                                  c.batch ? "1000" : "60", "--duration", dur,  "--quiet",  "--json",
                                  o.workdir + "/bench_clients_" + c.name + ".json"};
    if (c.batch) a.push_back("--batch");
    pids.push_back(bench::spawn(a, o.workdir + "/bench_clients_" + c.name + ".log"));
    clients.push_back(c);
  }
  for (std::size_t k = 0; k < clients.size(); ++k) {
    ClientResult& c = clients[k];
    c.exit_status = test::waitExit(pids[k]);
    const std::string j = test::slurp(o.workdir + "/bench_clients_" + c.name + ".json");
    c.granted = num(j, "", "granted_rate_hz");
    c.messages = num(j, "", "messages");
    c.achieved = num(j, "", "achieved_rate_hz");
    c.rate_error = num(j, "", "rate_error");
    c.missing = num(j, "", "missing");
    c.duplicates = num(j, "", "duplicates");
    c.samples = c.batch ? num(j, "", "samples") : 0;
    c.samples_missing = c.batch ? num(j, "", "samples_missing") : 0;
    c.lat_p50 = num(j, "latency_us", "p50");
    c.lat_p99 = num(j, "latency_us", "p99");
    c.lat_max = num(j, "latency_us", "max");
  }
  kill(server, SIGTERM);
  servo.push_back(readServo("load", test::commandLine(hargv), test::waitExit(server), stats));
  servo.push_back(baseline(o, url, "after"));

  const double base_p99 = 0.5 * (servo[0].p99 + servo[2].p99);
  const double ratio = servo[1].p99 / base_p99;
  double worst_rate = 0, worst_delivery = 1;
  bool all_ok = true;
  for (const ClientResult& c : clients) {
    worst_rate = std::max(worst_rate, std::abs(c.rate_error));
    const double got = c.batch ? c.samples / (c.samples + c.samples_missing) : 1.0;
    worst_delivery = std::min({worst_delivery, c.messages / (c.messages + c.missing), got});
    all_ok = all_ok && c.exit_status == 0;
  }
  std::fprintf(stderr,
               "bench_clients: worst rate error %.4f %%, worst delivery %.4f %%, compute p99 %.2f us loaded vs %.2f us "
               "alone: ratio %.3f\n",
               100 * worst_rate, 100 * worst_delivery, servo[1].p99, base_p99, ratio);

  if (!o.csv.empty()) {
    std::FILE* f = std::fopen(o.csv.c_str(), "w");
    if (!f) return std::fprintf(stderr, "bench_clients: cannot write %s\n", o.csv.c_str()), 1;
    std::fputs("client,stream,batch,rate_hz,granted_hz,messages,achieved_hz,rate_error,missing,duplicates,samples,"
               "samples_missing,latency_p50_us,latency_p99_us,latency_max_us,exit_status\n",
               f);
    for (const ClientResult& c : clients) std::fputs(csvRow(c).c_str(), f);
    std::fclose(f);
  }
  if (!o.json.empty()) {
    std::FILE* f = std::fopen(o.json.c_str(), "w");
    if (!f) return std::fprintf(stderr, "bench_clients: cannot write %s\n", o.json.c_str()), 1;
    std::fprintf(f, "{\n  \"seconds\": %g,\n  \"baseline_seconds\": %g,\n  \"url\": \"%s\",\n", o.seconds,
                 o.baseline_seconds, url.c_str());
    std::fprintf(f, "  \"compute_p99_ratio\": %.4f,\n  \"worst_rate_error\": %.6f,\n  \"worst_delivery\": %.6f,\n", ratio,
                 worst_rate, worst_delivery);
    std::fprintf(f, "  \"servo\": [\n");
    for (std::size_t k = 0; k < servo.size(); ++k) {
      const ServoResult& s = servo[k];
      std::fprintf(f,
                   "    {\"phase\": \"%s\", \"exit_status\": %d, \"sched_fifo\": %s, \"ticks\": %.0f, \"missed_ticks\": "
                   "%.0f, \"rate_hz\": %.3f, \"compute_us\": {\"p50\": %.3f, \"p99\": %.3f, \"p999\": %.3f, \"max\": "
                   "%.3f}, \"wake_p99_us\": %.1f, \"max_force_n\": %.4f}%s\n",
                   s.phase.c_str(), s.exit_status, s.fifo ? "true" : "false", s.ticks, s.missed, s.rate_hz, s.p50, s.p99,
                   s.p999, s.max, s.wake_p99, s.max_force, k + 1 < servo.size() ? "," : "");
    }
    std::fprintf(f, "  ],\n  \"clients\": [\n");
    for (std::size_t k = 0; k < clients.size(); ++k) {
      const ClientResult& c = clients[k];
      std::fprintf(f,
                   "    {\"client\": \"%s\", \"stream\": \"%s\", \"batch\": %s, \"rate_hz\": %g, \"granted_hz\": %g, "
                   "\"messages\": %.0f, \"achieved_hz\": %.4f, \"rate_error\": %.6f, \"missing\": %.0f, \"duplicates\": "
                   "%.0f, \"samples\": %.0f, \"samples_missing\": %.0f, \"latency_us\": {\"p50\": %.1f, \"p99\": %.1f, "
                   "\"max\": %.1f}, \"exit_status\": %d}%s\n",
                   c.name.c_str(), c.stream.c_str(), c.batch ? "true" : "false", c.rate, c.granted, c.messages,
                   c.achieved, c.rate_error, c.missing, c.duplicates, c.samples, c.samples_missing, c.lat_p50,
                   c.lat_p99, c.lat_max, c.exit_status, k + 1 < clients.size() ? "," : "");
    }
    std::fprintf(f, "  ],\n  \"load_command\": \"%s\"\n}\n", test::commandLine(hargv).c_str());
    std::fclose(f);
  }
  if (!o.md.empty()) {
    std::FILE* f = std::fopen(o.md.c_str(), "w");
    if (!f) return std::fprintf(stderr, "bench_clients: cannot write %s\n", o.md.c_str()), 1;
    std::fprintf(f, "| servo run | SCHED_FIFO | ticks | missed | compute p50 / p99 / p99.9 / max (µs) | wake p99 (µs) | max force (N) |\n");
    std::fprintf(f, "|---|---|---|---|---|---|---|\n");
    for (const ServoResult& s : servo) {
      std::fprintf(f, "| %s | %s | %.0f | %.0f | %.2f / %.2f / %.2f / %.1f | %.1f | %.3f |\n",
                   s.phase == "load" ? "16 clients" : ("no client, " + s.phase).c_str(), s.fifo ? "yes" : "no", s.ticks,
                   s.missed, s.p50, s.p99, s.p999, s.max, s.wake_p99, s.max_force);
    }
    std::fprintf(f, "\n**Compute p99 with 16 clients / without: %.3f** (%.2f µs / %.2f µs, the mean of the two runs "
                 "without; goal ≤ 1.10).\n\n", ratio, servo[1].p99, base_p99);
    // One row per kind of client: the worst of its group, and the group's totals.
    std::fprintf(f, "| clients | rate | messages (each) | achieved rate, worst | missing | samples (each) | samples "
                    "missing | latency p50 / p99 / max, worst (µs) |\n|---|---|---|---|---|---|---|---|\n");
    for (const bool batch : {true, false}) {
      double mmin = 1e300, mmax = 0, worst = 0, missing = 0, smin = 1e300, smax = 0, smiss = 0, p50 = 0, p99 = 0, mx = 0;
      int n = 0;
      for (const ClientResult& c : clients) {
        if (c.batch != batch) continue;
        ++n;
        mmin = std::min(mmin, c.messages);
        mmax = std::max(mmax, c.messages);
        if (std::abs(c.rate_error) >= std::abs(worst)) worst = c.rate_error;
        missing += c.missing;
        smin = std::min(smin, c.samples);
        smax = std::max(smax, c.samples);
        smiss += c.samples_missing;
        p50 = std::max(p50, c.lat_p50);
        p99 = std::max(p99, c.lat_p99);
        mx = std::max(mx, c.lat_max);
      }
      std::fprintf(f, "| %d × %s | %s | %.0f–%.0f | %+.4f %% | %.0f | %s | %s | %.0f / %.0f / %.0f |\n", n,
                   batch ? "CONTACT batched" : "DEVICE_STATE", batch ? "1000 Hz" : "60 Hz", mmin, mmax, 100 * worst,
                   missing, batch ? (std::to_string(long(smin)) + "–" + std::to_string(long(smax))).c_str() : "—",
                   batch ? std::to_string(long(smiss)).c_str() : "—", p50, p99, mx);
    }
    std::fprintf(f, "\n%s %g s each; worst rate error %.4f %%, worst delivery %.4f %% of messages and samples.\n",
                 all_ok ? "All 16 probe-clients exited 0;" : "NOT all probe-clients exited 0;", o.seconds,
                 100 * worst_rate, 100 * worst_delivery);
    std::fclose(f);
  }
  return all_ok ? 0 : 1;
}
