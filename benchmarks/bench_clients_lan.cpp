// Part 5c of docs/benchmarks.md: clients on other hosts (issue 31), on a virtual LAN inside this
// machine (tests/support/virtual_lan.hpp: one network namespace per host, veth cables to one
// bridge, 10.31.0.H/24, udpm with ttl=1). Measures, never asserts. Needs root (ip netns).
//
// Three runs of a fresh real-time hapticd on host 1, each --seconds long:
//   alone       no client: the servo's compute p99 to compare with;
//   one-host    the workload with every client on host 1 beside hapticd;
//   two-hosts   the workload split: half the clients on host 2, half on host 3;
// then, with --outage S, the two-host run again with host 2's cable pulled for S seconds at
// a third of the run. The workload is --clients N (default 32) per run, per host half of them:
// --batch-clients B (default 8 per host) batched CONTACT at 1 kHz, the rest DEVICE_STATE at 60 Hz.
// Per client: rate error, delivered share, time to admission, duplicates; per outage client:
// messages missing against the outage's own (rate x outage), i.e. how long after the cable came
// back its stream resumed, and whether it had to ask again (reconnects).
//
// Usage: bench_clients_lan --hapticd PATH --probe PATH --scene FILE [--seconds S] [--clients N]
//                          [--batch-clients B] [--outage S] [--port N] [--workdir DIR] [--json F] [--md F]
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

#include "base/program_main.hpp"
#include "benchmarks/proc_tools.hpp"
#include "tests/support/virtual_lan.hpp"

namespace {

using namespace thx;

constexpr char kHelp[] = R"(usage: bench_clients_lan --hapticd PATH --probe PATH --scene FILE [options]
hapticd on host 1 of a virtual LAN (network namespaces, needs root), probe-clients on one host and
on two others, and a pulled cable (docs/benchmarks.md, part 5c).
  --seconds S        length of each run (default 20)
  --clients N        clients per loaded run, split over the client hosts (default 32)
  --batch-clients B  of them per client host, batched CONTACT at 1 kHz (default 8); the rest
                     DEVICE_STATE at 60 Hz
  --outage S         pull host 2's cable for S seconds in a fourth run (default 2; 0: no such run)
  --port N           the LCM bus port (default 7941); hapticd takes the ones after it
  --workdir DIR      logs and the probes' JSON (default .)
  --json F, --md F   the results as JSON and as a Markdown table
)";

struct Options {
  std::string hapticd, probe, scene, workdir = ".", json, md;
  double seconds = 20, outage = 2;
  int clients = 32, batch_per_host = 8, port = 7941;
};

struct Client {
  std::string name;
  int host = 0;
  bool batch = false;
  double rate = 0, granted = 0, messages = 0, rate_error = 0, missing = 0, duplicates = 0, reconnects = 0;
  double admission_s = -1, delivered = 0;
  int exit_status = -1;
};

struct Run {
  std::string name;
  double servo_p99 = NAN, servo_max = NAN, missed = NAN, max_force = NAN;
  int exit_status = -1;
  std::vector<Client> clients;
  double outage_at_s = 0, outage_s = 0;
};

Options parse(const std::vector<std::string>& args) {
  Options o;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    auto value = [&] {
      if (i + 1 >= args.size()) throw UsageError(a + " needs a value");
      return args[++i];
    };
    auto number = [&](double lo, double hi) {
      const std::string v = value();
      char* end = nullptr;
      const double x = std::strtod(v.c_str(), &end);
      if (v.empty() || *end || !(x >= lo && x <= hi))
        throw UsageError(a + ": expected a number in [" + std::to_string(lo) + ", " + std::to_string(hi) +
                                          "], got '" + v + "'");
      return x;
    };
    if (a == "--hapticd") o.hapticd = value();
    else if (a == "--probe") o.probe = value();
    else if (a == "--scene") o.scene = value();
    else if (a == "--workdir") o.workdir = value();
    else if (a == "--json") o.json = value();
    else if (a == "--md") o.md = value();
    else if (a == "--seconds") o.seconds = number(3, 3600);
    else if (a == "--outage") o.outage = number(0, 60);
    else if (a == "--clients") o.clients = int(number(2, 64));
    else if (a == "--batch-clients") o.batch_per_host = int(number(0, 32));
    else if (a == "--port") o.port = int(number(1024, 65000));
    else throw UsageError("unknown argument '" + a + "'");
  }
  if (o.hapticd.empty() || o.probe.empty() || o.scene.empty())
    throw UsageError("--hapticd, --probe and --scene are required");
  return o;
}

double num(const std::string& json, const std::string& key) { return test::jsonNumber(json, key); }

// One run: hapticd on host 1, `clients` started on their hosts together, `outage` (host 2's cable
// pulled for outage_s at outage_at_s after the clients start) if outage_s > 0.
Run runOnce(const Options& o, test::VirtualLan& lan, Run run) {
  const std::string url = "udpm://239.255.76.67:" + std::to_string(o.port) + "?ttl=1&recv_buf_size=4194304";
  const std::string tag = o.workdir + "/lan_" + run.name;
  char seconds[32];
  std::snprintf(seconds, sizeof seconds, "%g", o.seconds);
  std::fprintf(stderr, "bench_clients_lan: %s: %zu clients for %g s%s\n", run.name.c_str(), run.clients.size(),
               o.seconds, run.outage_s > 0 ? ", host 2's cable pulled" : "");
  const pid_t server = bench::spawn(
      lan.on(1, {o.hapticd, "--scene", o.scene, "--duration", "0", "--quiet", "--lcm-url", url, "--stats-json",
                 tag + "_hapticd.json", "--flight-dir", o.workdir, "--max-clients", "64", "--max-bandwidth", "1000"}),
      tag + "_hapticd.log");
  std::this_thread::sleep_for(std::chrono::seconds(1));
  std::vector<pid_t> pids;
  for (const Client& c : run.clients) {
    std::vector<std::string> a = {o.probe, "--lcm-url", url, "--client-id", c.name, "--stream",
                                  c.batch ? "CONTACT" : "DEVICE_STATE", "--rate", c.batch ? "1000" : "60",
                                  "--duration", seconds, "--connect-timeout", "30", "--quiet",
                                  "--json", tag + "_" + c.name + ".json"};
    if (c.batch) a.push_back("--batch");
    pids.push_back(bench::spawn(lan.on(c.host, a), tag + "_" + c.name + ".log"));
  }
  if (run.outage_s > 0) {
    std::this_thread::sleep_for(std::chrono::duration<double>(run.outage_at_s));
    lan.unplug(2);
    std::this_thread::sleep_for(std::chrono::duration<double>(run.outage_s));
    lan.plug(2);
  }
  const double wait = run.clients.empty() ? o.seconds : o.seconds + 40;
  for (std::size_t k = 0; k < pids.size(); ++k) {
    Client& c = run.clients[k];
    c.exit_status = test::reap(pids[k], wait);
    const std::string j = test::slurp(tag + "_" + c.name + ".json");
    c.granted = num(j, "granted_rate_hz");
    c.messages = num(j, "messages");
    c.rate_error = num(j, "steady_rate_error");
    c.missing = num(j, "missing");
    c.duplicates = num(j, "duplicates");
    c.reconnects = num(j, "reconnects");
    c.admission_s = num(j, "admission_s");
    c.delivered = c.messages / std::max(1.0, c.messages + c.missing);
  }
  if (run.clients.empty()) std::this_thread::sleep_for(std::chrono::duration<double>(o.seconds));
  kill(server, SIGTERM);
  run.exit_status = test::reap(server, 30);
  const std::string s = test::slurp(tag + "_hapticd.json");
  run.servo_p99 = test::jsonNumber(s, "tick_compute_us", "p99").value_or(NAN);
  run.servo_max = test::jsonNumber(s, "tick_compute_us", "max").value_or(NAN);
  run.missed = num(s, "missed_ticks");
  run.max_force = num(s, "max_force_n");
  return run;
}

// The workload: per client host, batch_per_host batched 1 kHz clients, the rest at 60 Hz.
std::vector<Client> workload(const Options& o, const std::vector<int>& hosts) {
  std::vector<Client> out;
  const int per_host = o.clients / int(hosts.size());
  for (int h : hosts) {
    for (int k = 0; k < per_host; ++k) {
      Client c;
      c.host = h;
      c.batch = k < std::min(o.batch_per_host * 2 / int(hosts.size()), per_host);  // the same share on one host
      c.rate = c.batch ? 1000 : 60;
      c.name = std::string(c.batch ? "a" : "v") + std::to_string(h) + "_" + std::to_string(k);
      out.push_back(c);
    }
  }
  return out;
}

struct Summary {
  double worst_rate_error = 0, min_delivered = 1, max_admission = 0, duplicates = 0;
  int failed = 0;
};
Summary summarize(const Run& r, bool only_host3 = false) {
  Summary s;
  for (const Client& c : r.clients) {
    if (only_host3 && c.host != 3) continue;
    if (c.exit_status != 0) ++s.failed;
    s.worst_rate_error = std::max(s.worst_rate_error, std::abs(c.rate_error));
    s.min_delivered = std::min(s.min_delivered, c.delivered);
    s.max_admission = std::max(s.max_admission, c.admission_s);
    s.duplicates += c.duplicates;
  }
  return s;
}

void writeMd(const Options& o, const std::vector<Run>& runs) {
  std::FILE* f = std::fopen(o.md.c_str(), "w");
  if (!f) throw Error(Error::Kind::Io, o.md + ": cannot write");
  std::fprintf(f, "| run | clients | worst steady rate error | least delivered | slowest admission | duplicates | "
                  "servo p99 (µs) | vs alone | missed ticks | peak force (N) |\n|---|---|---|---|---|---|---|---|---|---|\n");
  const double alone = runs.front().servo_p99;
  for (const Run& r : runs) {
    const Summary s = summarize(r);
    std::fprintf(f, "| %s | %zu | %.3f %% | %.4f %% | %.3f s | %.0f | %.1f | %.2f | %.0f | %.2f |\n", r.name.c_str(),
                 r.clients.size(), 100 * s.worst_rate_error, 100 * s.min_delivered, s.max_admission, s.duplicates,
                 r.servo_p99, r.servo_p99 / alone, r.missed, r.max_force);
  }
  for (const Run& r : runs) {
    if (r.outage_s <= 0) continue;
    std::fprintf(f, "\nOutage: host 2's cable pulled for %g s, %g s after the clients started (%g s run).\n\n"
                    "| client | rate | missed messages | the outage's own | back after the cable (ms) | reconnects | "
                    "duplicates |\n|---|---|---|---|---|---|---|\n",
                 r.outage_s, r.outage_at_s, o.seconds);
    for (const Client& c : r.clients) {
      if (c.host != 2) continue;
      const double own = c.rate * r.outage_s;
      std::fprintf(f, "| %s | %g Hz | %.0f | %.0f | %.0f | %.0f | %.0f |\n", c.name.c_str(), c.rate, c.missing, own,
                   1000 * (c.missing - own) / c.rate, c.reconnects, c.duplicates);
    }
    const Summary other = summarize(r, true);
    std::fprintf(f, "\nHost 3 meanwhile: worst steady rate error %.3f %%, least delivered %.4f %%, %.0f duplicates.\n",
                 100 * other.worst_rate_error, 100 * other.min_delivered, other.duplicates);
  }
  std::fclose(f);
}

void writeJson(const Options& o, const std::vector<Run>& runs) {
  std::FILE* f = std::fopen(o.json.c_str(), "w");
  if (!f) throw Error(Error::Kind::Io, o.json + ": cannot write");
  std::fprintf(f, "{\n  \"seconds\": %g,\n  \"runs\": [\n", o.seconds);
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const Run& r = runs[i];
    std::fprintf(f, "    {\"name\": \"%s\", \"servo_p99_us\": %.3f, \"servo_max_us\": %.3f, \"missed_ticks\": %.0f, "
                    "\"max_force_n\": %.4f, \"outage_s\": %g, \"outage_at_s\": %g, \"clients\": [\n",
                 r.name.c_str(), r.servo_p99, r.servo_max, r.missed, r.max_force, r.outage_s, r.outage_at_s);
    for (std::size_t k = 0; k < r.clients.size(); ++k) {
      const Client& c = r.clients[k];
      std::fprintf(f, "      {\"name\": \"%s\", \"host\": %d, \"rate_hz\": %g, \"granted_hz\": %g, \"messages\": %.0f, "
                      "\"steady_rate_error\": %.6f, \"missing\": %.0f, \"delivered\": %.6f, \"duplicates\": %.0f, "
                      "\"reconnects\": %.0f, \"admission_s\": %.4f, \"exit_status\": %d}%s\n",
                   c.name.c_str(), c.host, c.rate, c.granted, c.messages, c.rate_error, c.missing, c.delivered,
                   c.duplicates, c.reconnects, c.admission_s, c.exit_status, k + 1 < r.clients.size() ? "," : "");
    }
    std::fprintf(f, "    ]}%s\n", i + 1 < runs.size() ? "," : "");
  }
  std::fprintf(f, "  ]\n}\n");
  std::fclose(f);
}

int run(const std::vector<std::string>& args) {
  const Options o = parse(args);
  test::VirtualLan lan(3);
  if (!lan.unavailable().empty()) throw Error(Error::Kind::Io, "no virtual LAN: " + lan.unavailable());
  std::vector<Run> runs;
  runs.push_back(runOnce(o, lan, Run{"alone", NAN, NAN, NAN, NAN, -1, {}, 0, 0}));
  runs.push_back(runOnce(o, lan, Run{"one host", NAN, NAN, NAN, NAN, -1, workload(o, {1}), 0, 0}));
  runs.push_back(runOnce(o, lan, Run{"two hosts", NAN, NAN, NAN, NAN, -1, workload(o, {2, 3}), 0, 0}));
  if (o.outage > 0) {
    runs.push_back(
        runOnce(o, lan, Run{"two hosts, outage", NAN, NAN, NAN, NAN, -1, workload(o, {2, 3}), o.seconds / 3, o.outage}));
  }
  if (!o.json.empty()) writeJson(o, runs);
  if (!o.md.empty()) writeMd(o, runs);
  if (o.md.empty() && o.json.empty()) {
    for (const Run& r : runs) {
      const Summary s = summarize(r);
      std::printf("%-20s %2zu clients  rate error <= %.3f %%  delivered >= %.4f %%  admission <= %.3f s  "
                  "duplicates %.0f  servo p99 %.1f us\n",
                  r.name.c_str(), r.clients.size(), 100 * s.worst_rate_error, 100 * s.min_delivered, s.max_admission,
                  s.duplicates, r.servo_p99);
    }
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return thx::runProgram("bench_clients_lan", kHelp, argc, argv, run); }
