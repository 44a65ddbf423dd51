// Part 4 of docs/benchmarks.md: wake-up latency of hapticd's 1 kHz loop beside cyclictest.
//
// Five runs of `seconds` each: cyclictest alone, hapticd alone (real time, not lock-step), the
// pair again, then both at once. cyclictest: SCHED_FIFO 80 (hapticd's servo priority), 1 ms interval, memory
// locked, clock_nanosleep on CLOCK_MONOTONIC with absolute deadlines, a 1 us histogram. hapticd's
// servo sleeps the same way (device/clock.cpp) and reports its wake latency (now - deadline) in
// --stats-json (0.1 us bins). Whether each actually ran SCHED_FIFO is read back: cyclictest's
// threads from /proc/<pid>/task/*/stat while it runs, hapticd from its stats.
//
// Usage: bench_latency --hapticd PATH [--scene F] [--seconds S] [--cyclictest PATH] [--workdir DIR]
//                      [--json F] [--csv F] [--md F]
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "benchmarks/bench_help.hpp"
#include "benchmarks/bench_rig.hpp"
#include "benchmarks/cyclictest_run.hpp"
#include "benchmarks/proc_tools.hpp"

namespace {

using namespace thx;
using bench::Job;
using bench::Latency;

bool parseHapticdStats(const std::string& js, Latency& l) {
  const auto p50 = test::jsonNumber(js, "wake_latency_us", "p50");
  if (!p50) return false;
  l.p50_us = *p50;
  l.p99_us = test::jsonNumber(js, "wake_latency_us", "p99").value_or(0);
  l.p999_us = test::jsonNumber(js, "wake_latency_us", "p999").value_or(0);
  l.max_us = test::jsonNumber(js, "wake_latency_us", "max").value_or(0);
  l.count = std::uint64_t(test::jsonNumber(js, "wake_latency_us", "count").value_or(0));
  l.fifo = test::jsonBool(js, "realtime", "sched_fifo").value_or(false);
  const double missed = test::jsonNumber(js, "", "missed_ticks").value_or(0);
  l.note = bench::fmt("missed ticks %.0f; tick compute p50 %.1f us, p99 %.1f us; memory locked: %s", missed,
                      test::jsonNumber(js, "tick_compute_us", "p50").value_or(0),
                      test::jsonNumber(js, "tick_compute_us", "p99").value_or(0),
                      test::jsonBool(js, "realtime", "memory_locked").value_or(false) ? "yes" : "no");
  return true;
}

Job startHapticd(const std::string& exe, const std::string& scene, int seconds, const std::string& workdir,
                 const std::string& tag) {
  Job j;
  j.out = workdir + "/lat_hapticd_" + tag + ".json";
  j.log = workdir + "/lat_hapticd_" + tag + ".log";
  std::remove(j.out.c_str());
  std::remove(j.log.c_str());
  j.argv = {exe, "--scene", scene, "--duration", std::to_string(seconds), "--quiet", "--stats-json", j.out,
            "--flight-dir", workdir};
  j.pid = bench::spawn(j.argv, j.log);
  return j;
}

Latency finishHapticd(const Job& j, const std::string& run) {
  Latency l;
  l.source = "hapticd";
  l.run = run;
  l.command = test::commandLine(j.argv);
  const int st = test::waitExit(j.pid);
  l.ok = st == 0 && parseHapticdStats(test::slurp(j.out), l);
  if (!l.ok) l.note = bench::fmt("hapticd failed (exit %d), see %s", st, j.log.c_str());
  return l;
}

std::string us(double v, bool integer) { return integer ? bench::fmt("%.0f", v) : bench::fmt("%.1f", v); }

}  // namespace

int main(int argc, char** argv) {
  thx::bench::exitOnHelp(argc, argv, R"(usage: bench_latency --hapticd PATH [--scene FILE] [--seconds S] [--cyclictest PATH] [--workdir DIR]
                     [--json F] [--csv F] [--md F]

Wake-up latency: cyclictest and hapticd's servo in real time (docs/benchmarks.md part 4).
benchmarks/run.sh BUILD_DIR latency runs it as the docs show.
)");
  std::string hapticd, scene = bench::sourceDir() + "/scenes/default.yaml", cyclictest = "cyclictest",
                       workdir = ".", json_path, csv_path, md_path;
  int seconds = 10;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i], val = argv[i + 1];
    if (a == "--hapticd") hapticd = val;
    else if (a == "--scene") scene = val;
    else if (a == "--seconds") seconds = std::max(1, std::atoi(val.c_str()));
    else if (a == "--cyclictest") cyclictest = val;
    else if (a == "--workdir") workdir = val;
    else if (a == "--json") json_path = val;
    else if (a == "--csv") csv_path = val;
    else if (a == "--md") md_path = val;
    else {
      std::fprintf(stderr, "bench_latency: unknown option %s\n", a.c_str());
      return 2;
    }
  }
  if (hapticd.empty()) {
    std::fprintf(stderr,
                 "usage: bench_latency --hapticd PATH [--scene F] [--seconds S] [--cyclictest PATH] [--workdir DIR] "
                 "[--json F] [--csv F] [--md F]\n");
    return 2;
  }

  std::vector<Latency> rows;
  try {
    // Back to back, alternating, twice: on a shared machine one pair can catch a disturbance the
    // other does not.
    for (int round = 1; round <= 2; ++round) {
      const std::string tag = "alone" + std::to_string(round), run = "alone #" + std::to_string(round);
      std::fprintf(stderr, "bench_latency: cyclictest alone (%d s), round %d\n", seconds, round);
      {
        const Job c = bench::startCyclictest(cyclictest, seconds, workdir, tag);
        std::optional<int> ended;
        const bool fifo = bench::sawFifo(c.pid, ended);
        rows.push_back(bench::finishCyclictest(c, run, fifo, ended));
      }
      std::fprintf(stderr, "bench_latency: hapticd alone (%d s, real time), round %d\n", seconds, round);
      rows.push_back(finishHapticd(startHapticd(hapticd, scene, seconds, workdir, tag), run));
    }
    std::fprintf(stderr, "bench_latency: both at once (%d s)\n", seconds);
    {
      const Job h = startHapticd(hapticd, scene, seconds, workdir, "concurrent");
      const Job c = bench::startCyclictest(cyclictest, seconds, workdir, "concurrent");
      std::optional<int> ended;
      const bool fifo = bench::sawFifo(c.pid, ended);
      rows.push_back(bench::finishCyclictest(c, "concurrent", fifo, ended));
      rows.push_back(finishHapticd(h, "concurrent"));
    }

    std::string csv = "source,run,ok,sched_fifo,count,overflows,min_us,avg_us,p50_us,p99_us,p999_us,max_us,command,note\n";
    for (const Latency& l : rows) {
      csv += bench::fmt("%s,%s,%s,%s,%llu,%llu,%.1f,%.1f,%.1f,%.1f,%.1f,%.1f,\"%s\",\"%s\"\n", l.source.c_str(),
                        l.run.c_str(), l.ok ? "true" : "false", l.fifo ? "true" : "false",
                        (unsigned long long)l.count, (unsigned long long)l.overflows, l.min_us, l.avg_us, l.p50_us,
                        l.p99_us, l.p999_us, l.max_us, l.command.c_str(), l.note.c_str());
    }
    if (!csv_path.empty()) bench::writeTextFile(csv_path, csv);

    std::string js = "{\n  \"benchmark\": \"wake-up latency: hapticd servo loop vs cyclictest\",\n";
    js += "  \"machine\": \"" + bench::machineDescription() + "\",\n  \"date\": \"" + bench::isoTimeNow() + "\",\n";
    js += bench::fmt("  \"seconds\": %d,\n  \"interval_us\": 1000,\n  \"runs\": [\n", seconds);
    for (std::size_t i = 0; i < rows.size(); ++i) {
      const Latency& l = rows[i];
      js += bench::fmt("    {\"source\": \"%s\", \"run\": \"%s\", \"ok\": %s, \"sched_fifo\": %s, \"count\": %llu, "
                       "\"overflows\": %llu, \"p50_us\": %.1f, \"p99_us\": %.1f, \"p999_us\": %.1f, \"max_us\": %.1f, "
                       "\"command\": \"%s\", \"note\": \"%s\"}%s\n",
                       l.source.c_str(), l.run.c_str(), l.ok ? "true" : "false", l.fifo ? "true" : "false",
                       (unsigned long long)l.count, (unsigned long long)l.overflows, l.p50_us, l.p99_us, l.p999_us,
                       l.max_us, l.command.c_str(), l.note.c_str(), i + 1 < rows.size() ? "," : "");
    }
    js += "  ]\n}\n";
    if (!json_path.empty()) bench::writeTextFile(json_path, js);

    if (!md_path.empty()) {
      std::string md = "Machine: " + bench::machineDescription() + "; measured " + bench::isoTimeNow() + ".\n\n";
      md += bench::fmt(
          "%d s each, 1 ms period, SCHED_FIFO priority 80 for both, absolute `clock_nanosleep` on CLOCK_MONOTONIC "
          "for both; latency = wake-up time − deadline (µs). cyclictest reports whole microseconds (truncated), "
          "hapticd 0.1 µs bins (upper edge).\n\n",
          seconds);
      md += "| run | program | SCHED_FIFO | samples | p50 µs | p99 µs | p99.9 µs | max µs | notes |\n";
      md += "|---|---|---|---|---|---|---|---|---|\n";
      for (const Latency& l : rows) {
        if (!l.ok) {
          md += bench::fmt("| %s | %s | %s | — | — | — | — | — | %s |\n", l.run.c_str(), l.source.c_str(),
                           l.fifo ? "yes" : "**no**", l.note.c_str());
          continue;
        }
        const bool ct = l.source == "cyclictest";
        md += bench::fmt("| %s | %s | %s | %llu | %s | %s | %s | %s | %s |\n", l.run.c_str(), l.source.c_str(),
                         l.fifo ? "yes" : "**no**", (unsigned long long)l.count, us(l.p50_us, ct).c_str(),
                         us(l.p99_us, ct).c_str(), us(l.p999_us, ct).c_str(), us(l.max_us, ct).c_str(),
                         ct ? (l.overflows ? bench::fmt("%llu above 10 ms", (unsigned long long)l.overflows).c_str()
                                           : l.note.c_str())
                            : l.note.c_str());
      }
      md += "\nCommands: `" + rows[0].command + "`; `" + rows[1].command + "` (paths as run by benchmarks/run.sh).\n";
      bench::writeTextFile(md_path, md);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_latency: %s\n", e.what());
    return 1;
  }
  for (const Latency& l : rows) {
    if (!l.ok) return 1;
  }
  return 0;
}
