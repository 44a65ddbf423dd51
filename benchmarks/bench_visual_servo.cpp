// bench_visual_servo (issue 15, docs/visual.md "Beside the servo"): what the visual client's live
// loop costs hapticd's servo. Each run starts hapticd in real time on a scene whose simulated hand
// keeps the pen moving (benchmarks/scenes/load_press.yaml: the live client then draws nearly every
// step), on a private LCM bus, and, in the runs "with visual", `visual-client --live --window`
// under xvfb-run beside it, rendering relief frames for the whole run. The servo's wake latency
// (hapticd --stats-json "wake_latency_us": wake-up minus deadline) is compared with the run
// without the client, back to back on the same machine. Runs: the servo thread SCHED_FIFO
// (hapticd as root or with CAP_SYS_NICE) and, with CAP_SYS_NICE dropped (setpriv), at normal
// priority; the client with llvmpipe on 2 threads and on 1 (LP_NUM_THREADS).
// Timing is measured here, never asserted (docs/design.md §4 rule 7).
#include <signal.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

#include "base/cli_number.hpp"
#include "base/error.hpp"
#include "benchmarks/bench_help.hpp"
#include "benchmarks/bench_rig.hpp"
#include "benchmarks/proc_tools.hpp"

namespace {

using namespace thx;

const char* const kHelp = R"(usage: bench_visual_servo --hapticd PATH --visual-client PATH [--scene F] [--seconds S]
                          [--search linear|maxmip] [--workdir DIR] [--json F] [--csv F] [--md F]

hapticd's servo wake-up latency (p50, p99, p99.9, max; missed ticks) alone and with
`visual-client --live --window` (under xvfb-run) drawing relief frames beside it, back to back:
servo SCHED_FIFO and at normal priority (CAP_SYS_NICE dropped with setpriv), the client with
LP_NUM_THREADS=2 and 1. Needs xvfb-run (Debian xvfb) and setpriv (util-linux); a multicast route.

  --hapticd PATH         the server         --visual-client PATH   the client
  --scene F              default benchmarks/scenes/load_press.yaml (the pen moves all run)
  --seconds S            per run (default 20)
  --search S             the client's relief search (default maxmip; shadows on)
  --workdir DIR          logs and per-run JSON (default /tmp)
)";

struct Run {
  std::string name;
  bool fifo = true;      // servo may take SCHED_FIFO
  int lp_threads = 0;    // 0: no visual client
};

struct Row {
  Run run;
  bool ok = false, servo_fifo = false;
  double p50 = 0, p99 = 0, p999 = 0, max = 0;
  unsigned long long ticks = 0, missed = 0;
  std::string client_summary, hapticd_command, client_command, note;
};

std::string uniqueUrl() {
  return "udpm://239.255.76.67:" + std::to_string(23000 + (getpid() % 500) * 2) + "?ttl=0&recv_buf_size=4194304";
}

Row runOne(const Run& run, const std::string& hapticd, const std::string& visual, const std::string& scene,
           int seconds, const std::string& search, const std::string& workdir) {
  Row row;
  row.run = run;
  const std::string url = uniqueUrl();
  const std::string stats = workdir + "/visual_servo_" + run.name + ".json";
  const std::string hlog = workdir + "/visual_servo_" + run.name + "_hapticd.log";
  const std::string vlog = workdir + "/visual_servo_" + run.name + "_visual.log";
  for (const std::string& f : {stats, hlog, vlog}) std::remove(f.c_str());
  std::vector<std::string> h;
  if (!run.fifo) h = {"setpriv", "--inh-caps=-sys_nice", "--bounding-set=-sys_nice", "--"};
  const std::vector<std::string> h_args = {hapticd, "--scene", scene, "--duration", std::to_string(seconds + 3),
                                           "--quiet", "--stats-json", stats, "--lcm-url", url, "--flight-max", "0"};
  h.insert(h.end(), h_args.begin(), h_args.end());
  row.hapticd_command = test::commandLine(h);
  std::fprintf(stderr, "bench_visual_servo: %s (%d s)\n", run.name.c_str(), seconds);
  const pid_t hp = bench::spawn(h, hlog);
  pid_t vp = -1;
  if (run.lp_threads > 0) {
    const std::vector<std::string> v = {"env", "LP_NUM_THREADS=" + std::to_string(run.lp_threads), "xvfb-run", "-a",
                                        "-s", "-screen 0 1280x720x24 -nolisten tcp", visual, "--scene", scene,
                                        "--live", "--window", "--lcm-url", url, "--search", search,
                                        "--duration", std::to_string(seconds), "--connect-timeout", "10"};
    row.client_command = test::commandLine(v);
    vp = bench::spawn(v, vlog);
  }
  const int hs = test::waitExit(hp);
  if (vp > 0) {
    const int vs = test::reap(vp, 30.0);
    if (vs != 0) row.note = bench::fmt("visual-client exit %d, see %s; ", vs, vlog.c_str());
    const std::string vl = test::slurp(vlog);
    std::smatch m;
    if (std::regex_search(vl, m, std::regex("loop steps [^\n]*"))) row.client_summary = m.str();
    else row.note += "no summary from visual-client, see " + vlog;
  }
  const std::string js = test::slurp(stats);
  row.ok = hs == 0 && test::jsonNumber(js, "", "ticks").has_value();
  if (!row.ok) {
    row.note += bench::fmt("hapticd failed (exit %d), see %s", hs, hlog.c_str());
    return row;
  }
  row.p50 = test::jsonNumber(js, "wake_latency_us", "p50").value_or(0);
  row.p99 = test::jsonNumber(js, "wake_latency_us", "p99").value_or(0);
  row.p999 = test::jsonNumber(js, "wake_latency_us", "p999").value_or(0);
  row.max = test::jsonNumber(js, "wake_latency_us", "max").value_or(0);
  row.ticks = (unsigned long long)test::jsonNumber(js, "", "ticks").value_or(0);
  row.missed = (unsigned long long)test::jsonNumber(js, "", "missed_ticks").value_or(0);
  row.servo_fifo = test::jsonBool(js, "realtime", "sched_fifo").value_or(false);
  return row;
}

int run(int argc, char** argv) {
  std::string hapticd, visual, scene = bench::sourceDir() + "/benchmarks/scenes/load_press.yaml", search = "maxmip";
  std::string workdir = "/tmp", json, csv, md;
  int seconds = 20;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw UsageError(a + ": missing value");
      return argv[++i];
    };
    if (a == "--hapticd") hapticd = value();
    else if (a == "--visual-client") visual = value();
    else if (a == "--scene") scene = value();
    else if (a == "--seconds") seconds = int(cli::parseInteger(a, value(), 2, 3600));
    else if (a == "--search") search = value();
    else if (a == "--workdir") workdir = value();
    else if (a == "--json") json = value();
    else if (a == "--csv") csv = value();
    else if (a == "--md") md = value();
    else throw UsageError("unknown option '" + a + "'");
  }
  if (hapticd.empty() || visual.empty()) throw UsageError("--hapticd PATH and --visual-client PATH are required");
  const std::vector<Run> runs = {{"fifo_alone", true, 0},   {"fifo_visual_lp2", true, 2},   {"fifo_visual_lp1", true, 1},
                                 {"normal_alone", false, 0}, {"normal_visual_lp2", false, 2}, {"normal_visual_lp1", false, 1}};
  std::vector<Row> rows;
  for (const Run& r : runs) {
    rows.push_back(runOne(r, hapticd, visual, scene, seconds, search, workdir));
    const Row& w = rows.back();
    std::fprintf(stderr, "  %-18s servo fifo %d: wake p50 %.1f p99 %.1f p99.9 %.1f max %.1f us, missed %llu / %llu  %s %s\n",
                 w.run.name.c_str(), w.servo_fifo, w.p50, w.p99, w.p999, w.max, w.missed, w.ticks,
                 w.client_summary.c_str(), w.note.c_str());
  }
  const auto client = [](const Row& r) { return r.run.lp_threads ? "LP_NUM_THREADS=" + std::to_string(r.run.lp_threads) : std::string("—"); };
  if (!csv.empty()) {
    std::ofstream f(csv);
    f << "run,servo_sched_fifo,visual_lp_threads,wake_p50_us,wake_p99_us,wake_p999_us,wake_max_us,ticks,missed_ticks,client_summary,note\n";
    for (const Row& r : rows)
      f << r.run.name << ',' << r.servo_fifo << ',' << r.run.lp_threads << ',' << r.p50 << ',' << r.p99 << ','
        << r.p999 << ',' << r.max << ',' << r.ticks << ',' << r.missed << ",\"" << r.client_summary << "\",\""
        << r.note << "\"\n";
    if (!f) throw Error(Error::Kind::Io, csv + ": write failed");
  }
  if (!json.empty()) {
    std::ofstream f(json);
    f << "{\n  \"benchmark\": \"hapticd wake latency alone and beside visual-client --live\",\n  \"machine\": \""
      << bench::machineDescription() << "\",\n  \"date\": \"" << bench::isoTimeNow() << "\",\n  \"seconds\": "
      << seconds << ",\n  \"scene\": \"" << scene << "\",\n  \"search\": \"" << search << "\",\n  \"runs\": [\n";
    for (std::size_t i = 0; i < rows.size(); ++i) {
      const Row& r = rows[i];
      f << "    {\"run\": \"" << r.run.name << "\", \"ok\": " << (r.ok ? "true" : "false")
        << ", \"servo_sched_fifo\": " << (r.servo_fifo ? "true" : "false") << ", \"visual_lp_threads\": "
        << r.run.lp_threads << ", \"wake_latency_us\": {\"p50\": " << r.p50 << ", \"p99\": " << r.p99
        << ", \"p999\": " << r.p999 << ", \"max\": " << r.max << "}, \"ticks\": " << r.ticks
        << ", \"missed_ticks\": " << r.missed << ", \"client_summary\": \"" << r.client_summary
        << "\", \"hapticd_command\": \"" << r.hapticd_command << "\", \"client_command\": \"" << r.client_command
        << "\", \"note\": \"" << r.note << "\"}" << (i + 1 < rows.size() ? "," : "") << "\n";
    }
    f << "  ]\n}\n";
    if (!f) throw Error(Error::Kind::Io, json + ": write failed");
  }
  if (!md.empty()) {
    std::ofstream f(md);
    f << "| servo | visual-client | wake p50 µs | p99 µs | p99.9 µs | max µs | missed ticks | client (frames) |\n"
         "|---|---|---|---|---|---|---|---|\n";
    for (const Row& r : rows)
      f << bench::fmt("| %s | %s | %.1f | %.1f | %.1f | %.1f | %llu / %llu | %s |\n",
                      r.servo_fifo ? "SCHED_FIFO" : "normal", client(r).c_str(), r.p50, r.p99, r.p999, r.max,
                      r.missed, r.ticks, r.ok ? r.client_summary.c_str() : r.note.c_str());
    if (!f) throw Error(Error::Kind::Io, md + ": write failed");
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return thx::bench::benchMain(argc, argv, kHelp, "bench_visual_servo", run); }
