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
//
// Sweep mode (issue 17), with --clients-list N1,N2,...: for each N, a fresh hapticd and N clients
// started together for --seconds, the workload split by --workload (mixed: N/4 batched CONTACT at
// 1 kHz, the rest DEVICE_STATE at 60 Hz, i.e. 16 + 48 at 64; half: N/2 and N/2; state60; batch1k).
// Per client: CPU time per second over a common window (/proc/PID/stat, from 2 s after the start
// to 1 s before the end) and over its own receiving window (getrusage in probe-client), rate
// error, delivered fraction, time to admission; per point: hapticd's CPU (per thread), the whole
// machine's busy fraction, UDP datagrams delivered to sockets and dropped (/proc/net/snmp), the
// servo's compute p99. Writes JSON (--json), one CSV row per client (--csv) and a summary table
// (--md). hapticd alone runs before and after the sweep for --baseline-seconds.
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "benchmarks/bench_help.hpp"
#include "benchmarks/proc_tools.hpp"

namespace {

using namespace thx;

struct Options {
  std::string hapticd, probe, scene, workdir = ".", json, csv, md;
  double seconds = 60, baseline_seconds = 30;
  int port = 7841;
  // Sweep mode (--clients-list): one hapticd run per client count, clients started together.
  std::vector<int> clients_list;
  std::string workload = "mixed";  // mixed, half, state60, batch1k
  std::string url_options;         // appended to the udpm URL's query (e.g. recv_buf_size=2097152)
  std::vector<std::string> hapticd_extra;  // --hapticd-arg X (repeatable), e.g. a prototype's option
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
               "[--baseline-seconds S] [--port N] [--workdir DIR] [--json F] [--csv F] [--md F]\n"
               "       sweep: ... --clients-list 1,2,4,...,64 [--workload mixed|half|state60|batch1k] "
               "[--url-options K=V&...] [--hapticd-arg ARG]...\n",
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
    else if (a == "--clients-list") {
      const std::string v = value();
      for (std::size_t p = 0; p < v.size();) {
        const std::size_t q = std::min(v.find(',', p), v.size());
        const int n = std::atoi(v.substr(p, q - p).c_str());
        if (n < 1 || n > 1000) usage("--clients-list: expected numbers 1..1000, got '" + v + "'");
        o.clients_list.push_back(n);
        p = q + 1;
      }
    } else if (a == "--workload") {
      o.workload = value();
      if (o.workload != "mixed" && o.workload != "half" && o.workload != "state60" && o.workload != "batch1k")
        usage("--workload: expected mixed, half, state60 or batch1k");
    } else if (a == "--url-options") o.url_options = value();
    else if (a == "--hapticd-arg") o.hapticd_extra.push_back(value());
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

// ---- sweep mode -------------------------------------------------------------------------------

// utime + stime of a process or thread from its stat file, in seconds; < 0 if it is gone.
double statCpu(const std::string& stat_path) {
  const std::string s = test::slurp(stat_path);
  const std::size_t p = s.rfind(')');
  if (p == std::string::npos) return -1;
  // After ") ": state(3) ppid pgrp session tty_nr tpgid flags minflt cminflt majflt cmajflt utime(14) stime(15)
  unsigned long long ut = 0, st = 0;
  if (std::sscanf(s.c_str() + p + 2, "%*c %*d %*d %*d %*d %*d %*u %*u %*u %*u %*u %llu %llu", &ut, &st) != 2) return -1;
  return double(ut + st) / double(sysconf(_SC_CLK_TCK));
}
double pidCpu(pid_t pid) { return statCpu("/proc/" + std::to_string(pid) + "/stat"); }

// Busy and total jiffies of the whole machine (/proc/stat, first line).
std::pair<double, double> machineJiffies() {
  const std::string s = test::slurp("/proc/stat");
  unsigned long long v[10] = {};
  std::sscanf(s.c_str(), "cpu %llu %llu %llu %llu %llu %llu %llu %llu %llu %llu", &v[0], &v[1], &v[2], &v[3], &v[4],
              &v[5], &v[6], &v[7], &v[8], &v[9]);
  double total = 0;
  for (int k = 0; k < 8; ++k) total += double(v[k]);
  return {total - double(v[3]) - double(v[4]), total};  // idle, iowait
}

// /proc/net/snmp "Udp:" counters by name (InDatagrams, RcvbufErrors, ...).
std::map<std::string, double> udpCounters() {
  std::istringstream in(test::slurp("/proc/net/snmp"));
  std::string line, names;
  std::map<std::string, double> out;
  while (std::getline(in, line)) {
    if (line.rfind("Udp: ", 0) != 0) continue;
    if (names.empty()) {
      names = line;
      continue;
    }
    std::istringstream n(names.substr(5)), v(line.substr(5));
    std::string key;
    double x;
    while (n >> key && v >> x) out[key] = x;
    break;
  }
  return out;
}

struct Sample {
  double t = 0;                         // monotonic seconds
  std::vector<double> clients;          // CPU s per client
  std::map<int, double> server_threads; // CPU s per hapticd thread
  double server = 0;
  std::pair<double, double> machine;
  std::map<std::string, double> udp;
};

double nowS() { return 1e-9 * double(std::chrono::steady_clock::now().time_since_epoch().count()); }

Sample takeSample(pid_t server, const std::vector<pid_t>& clients) {
  Sample s;
  s.t = nowS();
  for (pid_t p : clients) s.clients.push_back(pidCpu(p));
  s.server = pidCpu(server);
  for (const auto& [tid, name] : bench::threadNames(server))
    s.server_threads[tid] = statCpu("/proc/" + std::to_string(server) + "/task/" + std::to_string(tid) + "/stat");
  s.machine = machineJiffies();
  s.udp = udpCounters();
  return s;
}

struct SweepClient : ClientResult {
  double admission_s = -1, first_message_s = -1, cpu_pct = NAN, own_cpu_pct = NAN, delivered = 0;
  double steady_rate_error = 0;  // probe-client's rate from 2 s after its first message on
  std::string state;
};

struct SweepPoint {
  int n = 0, n_batch = 0;
  ServoResult servo;
  std::vector<SweepClient> clients;
  double window_s = 0, server_cpu_pct = 0, machine_busy_pct = 0, udp_in_per_s = 0, udp_rcvbuf_err_per_s = 0,
         udp_in_err_per_s = 0;
  std::vector<std::pair<int, double>> server_threads_pct;  // tid, CPU %
  std::map<int, int> server_policies;
};

int batchCount(const std::string& workload, int n) {
  if (workload == "state60") return 0;
  if (workload == "batch1k") return n;
  if (workload == "half") return n / 2;
  return (n + 2) / 4;  // mixed: 1 -> 0, 2 -> 1, 4 -> 1, ..., 64 -> 16
}

SweepPoint runPoint(const Options& o, const std::string& url, int n) {
  SweepPoint pt;
  pt.n = n;
  pt.n_batch = batchCount(o.workload, n);
  const std::string tag = "sweep" + std::to_string(n);
  const std::string stats = o.workdir + "/bench_clients_" + tag + ".json";
  auto hargv = hapticdArgv(o, url, stats, 0);
  hargv.insert(hargv.end(), {"--max-clients", std::to_string(std::max(32, n)), "--max-bandwidth", "1000"});
  hargv.insert(hargv.end(), o.hapticd_extra.begin(), o.hapticd_extra.end());
  std::fprintf(stderr, "bench_clients: N = %d (%d batched CONTACT 1 kHz, %d DEVICE_STATE 60 Hz) for %g s\n", n,
               pt.n_batch, n - pt.n_batch, o.seconds);
  const pid_t server = bench::spawn(hargv, o.workdir + "/bench_clients_" + tag + ".log");
  std::this_thread::sleep_for(std::chrono::milliseconds(1000));
  char dur[32], cto[32];
  std::snprintf(dur, sizeof dur, "%g", o.seconds);
  std::snprintf(cto, sizeof cto, "%g", o.seconds + 5);
  std::vector<pid_t> pids;
  for (int k = 0; k < n; ++k) {
    SweepClient c;
    c.batch = k < pt.n_batch;
    c.name = (c.batch ? "audio" : "visual") + std::to_string(k);
    c.stream = c.batch ? "CONTACT" : "DEVICE_STATE";
    c.rate = c.batch ? 1000 : 60;
    std::vector<std::string> a = {o.probe, "--lcm-url", url, "--client-id", c.name, "--stream", c.stream, "--rate",
                                  c.batch ? "1000" : "60", "--duration", dur, "--connect-timeout", cto, "--quiet",
                                  "--json", o.workdir + "/bench_clients_" + tag + "_" + c.name + ".json"};
    if (c.batch) a.push_back("--batch");
    pids.push_back(bench::spawn(a, o.workdir + "/bench_clients_" + tag + "_" + c.name + ".log"));
    pt.clients.push_back(c);
  }
  // A common window for every process: from 2 s after the start to 1 s before the earliest end.
  const double warm = std::min(2.0, 0.25 * o.seconds);
  std::this_thread::sleep_for(std::chrono::duration<double>(warm));
  const Sample a = takeSample(server, pids);
  std::this_thread::sleep_for(std::chrono::duration<double>(std::max(0.5, o.seconds - warm - 1.0)));
  const Sample b = takeSample(server, pids);
  pt.window_s = b.t - a.t;
  for (std::size_t k = 0; k < pids.size(); ++k) {
    if (a.clients[k] >= 0 && b.clients[k] >= 0) pt.clients[k].cpu_pct = 100 * (b.clients[k] - a.clients[k]) / pt.window_s;
  }
  pt.server_cpu_pct = 100 * (b.server - a.server) / pt.window_s;
  for (const auto& [tid, cpu] : b.server_threads) {
    auto it = a.server_threads.find(tid);
    if (it != a.server_threads.end()) pt.server_threads_pct.push_back({tid, 100 * (cpu - it->second) / pt.window_s});
  }
  pt.server_policies = bench::threadPolicies(server);
  pt.machine_busy_pct = 100 * (b.machine.first - a.machine.first) / std::max(1.0, b.machine.second - a.machine.second);
  auto rate = [&](const char* key) { return (b.udp.at(key) - a.udp.at(key)) / pt.window_s; };
  pt.udp_in_per_s = rate("InDatagrams");
  pt.udp_rcvbuf_err_per_s = rate("RcvbufErrors");
  pt.udp_in_err_per_s = rate("InErrors");

  for (std::size_t k = 0; k < pt.clients.size(); ++k) {
    SweepClient& c = pt.clients[k];
    c.exit_status = test::reap(pids[k], o.seconds + 30);
    const std::string j = test::slurp(o.workdir + "/bench_clients_" + tag + "_" + c.name + ".json");
    c.granted = num(j, "", "granted_rate_hz");
    c.messages = num(j, "", "messages");
    c.achieved = num(j, "", "achieved_rate_hz");
    c.rate_error = c.messages > 1 ? num(j, "", "rate_error") : -1.0;
    c.steady_rate_error = c.messages > 1 ? num(j, "", "steady_rate_error") : -1.0;
    c.missing = num(j, "", "missing");
    c.duplicates = num(j, "", "duplicates");
    c.samples = c.batch ? num(j, "", "samples") : 0;
    c.samples_missing = c.batch ? num(j, "", "samples_missing") : 0;
    c.lat_p50 = num(j, "latency_us", "p50");
    c.lat_p99 = num(j, "latency_us", "p99");
    c.lat_max = num(j, "latency_us", "max");
    c.admission_s = num(j, "", "admission_s");
    c.first_message_s = num(j, "", "first_message_s");
    const double wwall = num(j, "", "window_wall_s");
    c.own_cpu_pct = wwall > 0 ? 100 * num(j, "", "cpu_window_s") / wwall : NAN;
    c.state = test::jsonField(j, "state");
    if (c.batch) c.delivered = c.samples + c.samples_missing > 0 ? c.samples / (c.samples + c.samples_missing) : 0;
    else c.delivered = c.messages + c.missing > 0 ? c.messages / (c.messages + c.missing) : 0;
  }
  kill(server, SIGTERM);
  pt.servo = readServo(tag, test::commandLine(hargv), test::reap(server, 20), stats);
  return pt;
}

// hapticd alone for baseline_seconds, with its CPU over the middle of the run.
SweepPoint runAlone(const Options& o, const std::string& url, const std::string& phase) {
  SweepPoint pt;
  const std::string stats = o.workdir + "/bench_clients_" + phase + ".json";
  auto hargv = hapticdArgv(o, url, stats, o.baseline_seconds);
  hargv.insert(hargv.end(), o.hapticd_extra.begin(), o.hapticd_extra.end());
  std::fprintf(stderr, "bench_clients: %s: hapticd alone for %g s\n", phase.c_str(), o.baseline_seconds);
  const pid_t server = bench::spawn(hargv, o.workdir + "/bench_clients_" + phase + ".log");
  const double warm = std::min(1.0, 0.25 * o.baseline_seconds);
  std::this_thread::sleep_for(std::chrono::duration<double>(warm));
  const Sample a = takeSample(server, {});
  std::this_thread::sleep_for(std::chrono::duration<double>(std::max(0.5, o.baseline_seconds - warm - 1.0)));
  const Sample b = takeSample(server, {});
  pt.window_s = b.t - a.t;
  pt.server_cpu_pct = 100 * (b.server - a.server) / pt.window_s;
  pt.machine_busy_pct = 100 * (b.machine.first - a.machine.first) / std::max(1.0, b.machine.second - a.machine.second);
  pt.udp_in_per_s = (b.udp.at("InDatagrams") - a.udp.at("InDatagrams")) / pt.window_s;
  pt.servo = readServo(phase, test::commandLine(hargv), test::reap(server, o.baseline_seconds + 20), stats);
  return pt;
}

struct ClassSummary {
  int n = 0, admitted = 0;
  double cpu_mean = 0, cpu_max = 0, own_cpu_mean = 0, worst_rate = 0, worst_steady = 0, min_delivered = 1, adm_max = 0,
         adm_p50 = 0;
};

ClassSummary summarize(const SweepPoint& pt, bool batch) {
  ClassSummary s;
  std::vector<double> adm;
  int own_n = 0;
  for (const SweepClient& c : pt.clients) {
    if (c.batch != batch) continue;
    ++s.n;
    if (c.state == "active" && c.messages > 1) ++s.admitted;
    if (std::isfinite(c.cpu_pct)) {
      s.cpu_mean += c.cpu_pct;
      s.cpu_max = std::max(s.cpu_max, c.cpu_pct);
    }
    if (std::isfinite(c.own_cpu_pct)) {
      s.own_cpu_mean += c.own_cpu_pct;
      ++own_n;
    }
    if (std::abs(c.rate_error) > std::abs(s.worst_rate)) s.worst_rate = c.rate_error;
    if (std::abs(c.steady_rate_error) > std::abs(s.worst_steady)) s.worst_steady = c.steady_rate_error;
    s.min_delivered = std::min(s.min_delivered, c.delivered);
    adm.push_back(c.admission_s < 0 ? INFINITY : c.admission_s);
  }
  if (s.n) s.cpu_mean /= s.n;
  if (own_n) s.own_cpu_mean /= own_n;
  if (!adm.empty()) {
    std::sort(adm.begin(), adm.end());
    s.adm_p50 = adm[adm.size() / 2];
    s.adm_max = adm.back();
  }
  return s;
}

int runSweep(const Options& o, const std::string& url) {
  std::vector<SweepPoint> alone, points;
  alone.push_back(runAlone(o, url, "before"));
  for (int n : o.clients_list) {
    points.push_back(runPoint(o, url, n));
    const SweepPoint& pt = points.back();
    const ClassSummary b = summarize(pt, true), v = summarize(pt, false);
    std::fprintf(stderr,
                 "bench_clients: N=%d: client CPU %% mean (1k %.2f, 60Hz %.2f), hapticd %.1f %%, machine %.0f %%, "
                 "UDP in %.0f/s, rcvbuf drops %.0f/s, admitted %d/%d + %d/%d, worst rate %.2f %% / %.2f %%, "
                 "servo p99 %.2f us\n",
                 n, b.cpu_mean, v.cpu_mean, pt.server_cpu_pct, pt.machine_busy_pct, pt.udp_in_per_s,
                 pt.udp_rcvbuf_err_per_s, b.admitted, b.n, v.admitted, v.n, 100 * b.worst_rate, 100 * v.worst_rate,
                 pt.servo.p99);
  }
  alone.push_back(runAlone(o, url, "after"));
  const double base_p99 = 0.5 * (alone[0].servo.p99 + alone[1].servo.p99);

  if (!o.csv.empty()) {
    std::FILE* f = std::fopen(o.csv.c_str(), "w");
    if (!f) return std::fprintf(stderr, "bench_clients: cannot write %s\n", o.csv.c_str()), 1;
    std::fputs("workload,n,client,stream,batch,rate_hz,granted_hz,state,admission_s,first_message_s,messages,"
               "achieved_hz,rate_error,steady_rate_error,missing,samples,samples_missing,delivered,cpu_pct,own_cpu_pct,latency_p50_us,"
               "latency_p99_us,exit_status,server_cpu_pct,machine_busy_pct,udp_in_per_s,udp_rcvbuf_err_per_s,"
               "servo_p99_us\n",
               f);
    for (const SweepPoint& pt : points)
      for (const SweepClient& c : pt.clients)
        std::fprintf(f, "%s,%d,%s,%s,%d,%g,%g,%s,%.4f,%.4f,%.0f,%.4f,%.6f,%.6f,%.0f,%.0f,%.0f,%.6f,%.3f,%.3f,%.1f,%.1f,%d,"
                        "%.2f,%.1f,%.0f,%.0f,%.3f\n",
                     o.workload.c_str(), pt.n, c.name.c_str(), c.stream.c_str(), int(c.batch), c.rate, c.granted,
                     c.state.c_str(), c.admission_s, c.first_message_s, c.messages, c.achieved, c.rate_error,
                     c.steady_rate_error, c.missing, c.samples, c.samples_missing, c.delivered, c.cpu_pct, c.own_cpu_pct, c.lat_p50,
                     c.lat_p99, c.exit_status, pt.server_cpu_pct, pt.machine_busy_pct, pt.udp_in_per_s,
                     pt.udp_rcvbuf_err_per_s, pt.servo.p99);
    std::fclose(f);
  }
  if (!o.json.empty()) {
    std::FILE* f = std::fopen(o.json.c_str(), "w");
    if (!f) return std::fprintf(stderr, "bench_clients: cannot write %s\n", o.json.c_str()), 1;
    std::fprintf(f, "{\n  \"mode\": \"sweep\",\n  \"workload\": \"%s\",\n  \"seconds\": %g,\n  \"url\": \"%s\",\n",
                 o.workload.c_str(), o.seconds, url.c_str());
    std::fprintf(f, "  \"alone\": [\n");
    for (std::size_t k = 0; k < alone.size(); ++k)
      std::fprintf(f, "    {\"phase\": \"%s\", \"server_cpu_pct\": %.2f, \"machine_busy_pct\": %.1f, \"udp_in_per_s\": %.0f, "
                      "\"compute_p99_us\": %.3f, \"missed_ticks\": %.0f}%s\n",
                   alone[k].servo.phase.c_str(), alone[k].server_cpu_pct, alone[k].machine_busy_pct,
                   alone[k].udp_in_per_s, alone[k].servo.p99, alone[k].servo.missed, k + 1 < alone.size() ? "," : "");
    std::fprintf(f, "  ],\n  \"points\": [\n");
    for (std::size_t p = 0; p < points.size(); ++p) {
      const SweepPoint& pt = points[p];
      std::fprintf(f, "    {\"n\": %d, \"n_batch\": %d, \"window_s\": %.3f, \"server_cpu_pct\": %.2f, \"server_threads\": [",
                   pt.n, pt.n_batch, pt.window_s, pt.server_cpu_pct);
      for (std::size_t t = 0; t < pt.server_threads_pct.size(); ++t) {
        const auto pol = pt.server_policies.find(pt.server_threads_pct[t].first);
        std::fprintf(f, "%s{\"tid\": %d, \"policy\": %d, \"cpu_pct\": %.2f}", t ? ", " : "", pt.server_threads_pct[t].first,
                     pol == pt.server_policies.end() ? -1 : pol->second, pt.server_threads_pct[t].second);
      }
      std::fprintf(f, "],\n     \"machine_busy_pct\": %.1f, \"udp_in_per_s\": %.0f, \"udp_rcvbuf_err_per_s\": %.0f, "
                      "\"udp_in_err_per_s\": %.0f,\n     \"servo\": {\"compute_p50_us\": %.3f, \"compute_p99_us\": %.3f, "
                      "\"compute_p99_ratio\": %.4f, \"missed_ticks\": %.0f, \"sched_fifo\": %s},\n     \"clients\": [\n",
                   pt.machine_busy_pct, pt.udp_in_per_s, pt.udp_rcvbuf_err_per_s, pt.udp_in_err_per_s, pt.servo.p50,
                   pt.servo.p99, pt.servo.p99 / base_p99, pt.servo.missed, pt.servo.fifo ? "true" : "false");
      for (std::size_t k = 0; k < pt.clients.size(); ++k) {
        const SweepClient& c = pt.clients[k];
        std::fprintf(f, "      {\"client\": \"%s\", \"stream\": \"%s\", \"batch\": %s, \"rate_hz\": %g, \"granted_hz\": %g, "
                        "\"state\": \"%s\", \"admission_s\": %.4f, \"first_message_s\": %.4f, \"messages\": %.0f, "
                        "\"rate_error\": %.6f, \"steady_rate_error\": %.6f, \"delivered\": %.6f, \"cpu_pct\": %.3f, \"own_cpu_pct\": %.3f, "
                        "\"latency_p99_us\": %.1f, \"exit_status\": %d}%s\n",
                     c.name.c_str(), c.stream.c_str(), c.batch ? "true" : "false", c.rate, c.granted, c.state.c_str(),
                     c.admission_s, c.first_message_s, c.messages, c.rate_error, c.steady_rate_error, c.delivered,
                     std::isfinite(c.cpu_pct) ? c.cpu_pct : -1.0, std::isfinite(c.own_cpu_pct) ? c.own_cpu_pct : -1.0,
                     c.lat_p99, c.exit_status, k + 1 < pt.clients.size() ? "," : "");
      }
      std::fprintf(f, "     ]}%s\n", p + 1 < points.size() ? "," : "");
    }
    std::fprintf(f, "  ]\n}\n");
    std::fclose(f);
  }
  std::string md;
  char line[1024];
  std::snprintf(line, sizeof line,
                "| N | class | admitted | CPU/client mean (max) %% | own-window CPU %% | rate error, worst: whole run / "
                "after 2 s | delivered, worst | admission p50 / max (s) | hapticd CPU %% | machine busy %% | UDP datagrams in /s "
                "| rcvbuf drops /s | servo p99 µs (ratio) |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  md += line;
  for (const SweepPoint& pt : points) {
    for (const bool batch : {true, false}) {
      const ClassSummary s = summarize(pt, batch);
      if (s.n == 0) continue;
      std::snprintf(line, sizeof line,
                    "| %d | %d × %s | %d | %.2f (%.2f) | %.2f | %+.2f %% / %+.2f %% | %.2f %% | %.3f / %s | %.1f | %.0f | "
                    "%.0f | %.0f | %.2f (%.2f) |\n",
                    pt.n, s.n, batch ? "CONTACT batch 1 kHz" : "DEVICE_STATE 60 Hz", s.admitted, s.cpu_mean, s.cpu_max,
                    s.own_cpu_mean, 100 * s.worst_rate, 100 * s.worst_steady, 100 * s.min_delivered, s.adm_p50,
                    std::isfinite(s.adm_max) ? (std::to_string(s.adm_max).substr(0, 5)).c_str() : "never",
                    pt.server_cpu_pct, pt.machine_busy_pct, pt.udp_in_per_s, pt.udp_rcvbuf_err_per_s, pt.servo.p99,
                    pt.servo.p99 / base_p99);
      md += line;
    }
  }
  std::snprintf(line, sizeof line,
                "\nhapticd alone: CPU %.1f %% / %.1f %%, compute p99 %.2f / %.2f µs (before / after); workload %s, %g s "
                "per point, %s\n",
                alone[0].server_cpu_pct, alone[1].server_cpu_pct, alone[0].servo.p99, alone[1].servo.p99,
                o.workload.c_str(), o.seconds, url.c_str());
  md += line;
  std::fputs(md.c_str(), stdout);
  if (!o.md.empty()) {
    std::FILE* f = std::fopen(o.md.c_str(), "w");
    if (!f) return std::fprintf(stderr, "bench_clients: cannot write %s\n", o.md.c_str()), 1;
    std::fputs(md.c_str(), f);
    std::fclose(f);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  thx::bench::exitOnHelp(argc, argv, R"(usage: bench_clients --hapticd PATH --probe PATH --scene FILE [--seconds S] [--baseline-seconds S]
                     [--port N] [--workdir DIR] [--json F] [--csv F] [--md F]
       sweep: ... --clients-list 1,2,4,...,64 [--workload mixed|half|state60|batch1k]
                  [--url-options K=V&...] [--hapticd-arg ARG]...

hapticd under client load (docs/benchmarks.md parts 5 and 5b): probe-clients against a real-time
hapticd, each client's rate, delivery, latency and CPU, the servo's compute p99 against hapticd
alone. Measures, never asserts. benchmarks/run.sh BUILD_DIR clients runs it as the docs show.
)");
  const Options o = parse(argc, argv);
  // --url-options is appended to the query; ttl=0 unless it names a ttl itself.
  std::string url = "udpm://239.255.76.67:" + std::to_string(o.port) + "?";
  if (o.url_options.find("ttl=") == std::string::npos) url += "ttl=0";
  if (!o.url_options.empty()) url += (url.back() == '?' ? "" : "&") + o.url_options;
  if (!o.clients_list.empty()) return runSweep(o, url);
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
