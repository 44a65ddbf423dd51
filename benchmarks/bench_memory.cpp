// Part 3 of docs/benchmarks.md: hapticd's resident and locked memory with a 1024² relief map.
//
// Runs `hapticd --lockstep --stats-json` on benchmarks/scenes/relief1024.yaml (and, for
// comparison, with --mlock-eager, --no-mlock, --no-lcm, both, and on the 512² default scene), reads the
// rss_bytes / locked_bytes / texture_bytes it reports, and while it runs samples
// /proc/<pid>/smaps (keeping the sample with the largest resident total) to say what the memory is:
// the texture, thread stacks, the publication ring and flight recorder, the hapticd binary,
// shared libraries, other heap/anonymous memory.
//
// Usage: bench_memory --hapticd PATH [--scene F] [--baseline-scene F] [--workdir DIR]
//                     [--json F] [--csv F] [--md F]
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <climits>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <thread>
#include <vector>

#include "benchmarks/bench_help.hpp"
#include "benchmarks/bench_rig.hpp"
#include "benchmarks/proc_tools.hpp"
#include "server/flight_recorder.hpp"
#include "server/tick_record.hpp"

namespace {

using namespace thx;

constexpr std::int64_t kThreadStack = 512 * 1024;  // hapticd main(): pthread_setattr_default_np
constexpr std::int64_t kRingSlots = 1024;          // hapticd run(): SpscRing<TickRecord>(1024), 1 s of ticks
constexpr std::int64_t kFlightTicks = 1000;        // one second at 1 kHz, two buffers
constexpr double kMB = 1e6;

struct Breakdown {
  std::int64_t rss = 0, locked = 0;
  std::int64_t binary = 0, libs = 0, heap = 0, main_stack = 0, kernel = 0;
  std::int64_t texture = 0, stacks = 0, ring = 0, flight = 0, other_anon = 0;
  int stack_count = 0;
  std::map<std::string, std::int64_t> lib_rss;
};

struct Variant {
  std::string name, scene;
  std::vector<std::string> flags;
};

struct Outcome {
  Variant v;
  std::string command, command_rt;
  int exit_status = -1;
  std::int64_t rss = -1, locked = -1, texture = -1, hwm = -1, rss_rt = -1;
  int threads = 0;
  bool mlock = false;
  Breakdown b;
};

Breakdown classify(const std::vector<bench::Mapping>& maps, const std::string& binary_path,
                   std::int64_t texture_bytes) {
  Breakdown b;
  std::int64_t anon = 0;
  for (std::size_t i = 0; i < maps.size(); ++i) {
    const bench::Mapping& m = maps[i];
    b.rss += m.rss;
    b.locked += m.locked;
    if (m.path == binary_path) {
      b.binary += m.rss;
    } else if (!m.path.empty() && m.path[0] == '/') {
      b.libs += m.rss;
      b.lib_rss[m.path.substr(m.path.rfind('/') + 1)] += m.rss;
    } else if (m.path == "[heap]") {
      b.heap += m.rss;
    } else if (m.path == "[stack]") {
      b.main_stack += m.rss;
    } else if (!m.path.empty() && m.path[0] == '[') {
      b.kernel += m.rss;
    } else {
      // Anonymous. A thread stack is the rw mapping right above its guard page, 512 KiB together
      // (glibc maps stacks with MAP_STACK, so they do not merge with their neighbours).
      const bool guarded = i > 0 && maps[i - 1].end == m.start && maps[i - 1].perms.rfind("---", 0) == 0;
      const std::int64_t with_guard = m.size + (guarded ? maps[i - 1].size : 0);
      if (guarded && m.perms.rfind("rw", 0) == 0 && with_guard >= kThreadStack - 4096 &&
          with_guard <= kThreadStack + 8192) {
        b.stacks += m.rss;
        ++b.stack_count;
      } else {
        anon += m.rss;
      }
    }
  }
  // The kernel merges neighbouring anonymous mappings (the texture, the ring and the flight
  // recorder end up in one VMA), so the big allocations are attributed by their known sizes:
  // all three are written when they are constructed, so they are resident in full.
  std::int64_t pool = anon + b.heap;
  auto take = [&](std::int64_t bytes) {
    const std::int64_t t = std::min(bytes, pool);
    pool -= t;
    return t;
  };
  b.texture = take(texture_bytes);
  b.ring = take(kRingSlots * std::int64_t(sizeof(srv::TickRecord)));
  b.flight = take(2 * kFlightTicks * std::int64_t(sizeof(srv::FlightRecorder::FlightRecord)));
  b.other_anon = pool;  // malloc'd scene/LCM/GLib/yaml data, malloc's free space, small mappings
  b.heap = 0;
  return b;
}

struct Run {
  int exit_status = -1;
  std::string stats;                 // the --stats-json text
  std::vector<bench::Mapping> maps;  // smaps sample with the largest resident total
  int threads = 0;
  std::int64_t hwm = -1;
};

Run launch(const std::vector<std::string>& argv, const std::string& log, double sample_after_s) {
  Run r;
  const pid_t pid = bench::spawn(argv, log);
  const auto t0 = std::chrono::steady_clock::now();
  std::int64_t best_rss = -1;
  for (;;) {
    if (auto st = test::pollExit(pid)) {
      r.exit_status = *st;
      break;
    }
    if (sample_after_s >= 0 &&
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() >= sample_after_s) {
      std::vector<bench::Mapping> maps = bench::readSmaps(pid);
      std::int64_t rss = 0;
      for (const auto& m : maps) rss += m.rss;
      if (rss > best_rss) {
        best_rss = rss;
        r.maps = std::move(maps);
        r.threads = int(bench::statusField(pid, "Threads"));
        r.hwm = bench::statusField(pid, "VmHWM");
      }
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return r;
}

Outcome runOne(const std::string& hapticd, const Variant& v, const std::string& workdir) {
  Outcome o;
  o.v = v;
  char resolved[PATH_MAX];
  const std::string binary = realpath(hapticd.c_str(), resolved) ? resolved : hapticd;

  // 1. The numbers hapticd reports itself, lock-step, the scene's own duration.
  const std::string stats = workdir + "/mem_" + v.name + ".json";
  std::remove(stats.c_str());
  std::vector<std::string> argv{hapticd, "--scene", v.scene, "--lockstep", "--quiet", "--stats-json", stats,
                                "--flight-dir", workdir};
  argv.insert(argv.end(), v.flags.begin(), v.flags.end());
  o.command = test::commandLine(argv);
  std::fprintf(stderr, "bench_memory: %s\n", o.command.c_str());
  const Run lock = launch(argv, workdir + "/mem_" + v.name + ".log", -1.0);
  const std::string js = test::slurp(stats);
  if (lock.exit_status != 0 || js.empty()) {
    throw std::runtime_error("hapticd failed (exit " + std::to_string(lock.exit_status) + "), see " + workdir +
                             "/mem_" + v.name + ".log");
  }
  o.exit_status = lock.exit_status;
  o.rss = std::int64_t(test::jsonNumber(js, "", "rss_bytes").value_or(-1));
  o.locked = std::int64_t(test::jsonNumber(js, "", "locked_bytes").value_or(-1));
  o.texture = std::int64_t(test::jsonNumber(js, "", "texture_bytes").value_or(-1));
  o.mlock = test::jsonBool(js, "realtime", "memory_locked").value_or(false);

  // 2. What that memory is: the same flags in real time for 2 s (lock-step finishes too fast to
  //    watch), /proc/<pid>/smaps sampled from 0.8 s on.
  const std::string stats_rt = workdir + "/mem_" + v.name + "_rt.json";
  std::vector<std::string> argv_rt{hapticd, "--scene", v.scene, "--duration", "2", "--quiet", "--stats-json",
                                   stats_rt, "--flight-dir", workdir};
  argv_rt.insert(argv_rt.end(), v.flags.begin(), v.flags.end());
  o.command_rt = test::commandLine(argv_rt);
  std::fprintf(stderr, "bench_memory: %s (sampling /proc/<pid>/smaps)\n", o.command_rt.c_str());
  const Run rt = launch(argv_rt, workdir + "/mem_" + v.name + "_rt.log", 0.8);
  if (rt.exit_status != 0 || rt.maps.empty()) {
    throw std::runtime_error("hapticd (real time) failed or could not be sampled, see " + workdir + "/mem_" + v.name +
                             "_rt.log");
  }
  o.rss_rt = std::int64_t(test::jsonNumber(test::slurp(stats_rt), "", "rss_bytes").value_or(-1));
  o.threads = rt.threads;
  o.hwm = rt.hwm;
  o.b = classify(rt.maps, binary, o.texture);
  return o;
}

std::string mb(std::int64_t b) { return bench::fmt("%.2f", double(b) / kMB); }

}  // namespace

int main(int argc, char** argv) {
  thx::bench::exitOnHelp(argc, argv, R"(usage: bench_memory --hapticd PATH [--scene FILE] [--baseline-scene FILE] [--workdir DIR]
                    [--json F] [--csv F] [--md F]

hapticd's resident and locked memory, and what it is made of (docs/benchmarks.md part 3).
benchmarks/run.sh BUILD_DIR memory runs it as the docs show.
)");
  std::string hapticd, scene = bench::sourceDir() + "/benchmarks/scenes/relief1024.yaml",
                       baseline = bench::sourceDir() + "/scenes/default.yaml", workdir = ".", json_path, csv_path,
                       md_path;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i], val = argv[i + 1];
    if (a == "--hapticd") hapticd = val;
    else if (a == "--scene") scene = val;
    else if (a == "--baseline-scene") baseline = val;
    else if (a == "--workdir") workdir = val;
    else if (a == "--json") json_path = val;
    else if (a == "--csv") csv_path = val;
    else if (a == "--md") md_path = val;
    else {
      std::fprintf(stderr, "bench_memory: unknown option %s\n", a.c_str());
      return 2;
    }
  }
  if (hapticd.empty()) {
    std::fprintf(stderr,
                 "usage: bench_memory --hapticd PATH [--scene F] [--baseline-scene F] [--workdir DIR] [--json F] "
                 "[--csv F] [--md F]\n");
    return 2;
  }

  const std::vector<Variant> variants{
      {"relief1024", scene, {}},
      {"relief1024_mlock_eager", scene, {"--mlock-eager"}},
      {"relief1024_no_mlock", scene, {"--no-mlock"}},
      {"relief1024_no_lcm", scene, {"--no-lcm"}},
      {"relief1024_no_mlock_no_lcm", scene, {"--no-mlock", "--no-lcm"}},
      {"default512", baseline, {}},
  };
  std::vector<Outcome> out;
  try {
    for (const Variant& v : variants) out.push_back(runOne(hapticd, v, workdir));

    const std::int64_t tick_record = std::int64_t(sizeof(srv::TickRecord));
    const std::int64_t flight_record = std::int64_t(sizeof(srv::FlightRecorder::FlightRecord));
    std::string csv =
        "variant,flags,memory_locked,rss_bytes,locked_bytes,texture_bytes,rt_rss_bytes,rt_vm_hwm_bytes,rt_threads,smaps_rss,"
        "smaps_locked,"
        "texture_rss,thread_stacks_rss,thread_stacks,main_stack_rss,ring_rss,flight_recorder_rss,binary_rss,"
        "shared_libs_rss,heap_rss,other_anon_rss,kernel_rss\n";
    for (const Outcome& o : out) {
      std::string flags;
      for (const auto& f : o.v.flags) flags += (flags.empty() ? "" : " ") + f;
      const Breakdown& b = o.b;
      csv += bench::fmt("%s,%s,%s,%lld,%lld,%lld,%lld,%lld,%d,%lld,%lld,%lld,%lld,%d,%lld,%lld,%lld,%lld,%lld,%lld,%lld,%lld\n",
                        o.v.name.c_str(), flags.c_str(), o.mlock ? "true" : "false", (long long)o.rss,
                        (long long)o.locked, (long long)o.texture, (long long)o.rss_rt, (long long)o.hwm, o.threads,
                        (long long)b.rss,
                        (long long)b.locked, (long long)b.texture, (long long)b.stacks, b.stack_count,
                        (long long)b.main_stack, (long long)b.ring, (long long)b.flight, (long long)b.binary,
                        (long long)b.libs, (long long)b.heap, (long long)b.other_anon, (long long)b.kernel);
    }
    if (!csv_path.empty()) bench::writeTextFile(csv_path, csv);

    std::string js = "{\n  \"benchmark\": \"hapticd resident and locked memory\",\n";
    js += "  \"machine\": \"" + bench::machineDescription() + "\",\n  \"date\": \"" + bench::isoTimeNow() + "\",\n";
    js += bench::fmt("  \"tick_record_bytes\": %lld,\n  \"flight_record_bytes\": %lld,\n  \"goal_rss_bytes\": 16000000,\n"
                     "  \"runs\": [\n",
                     (long long)tick_record, (long long)flight_record);
    for (std::size_t i = 0; i < out.size(); ++i) {
      const Outcome& o = out[i];
      const Breakdown& b = o.b;
      js += bench::fmt("    {\"variant\": \"%s\", \"command\": \"%s\", \"memory_locked\": %s, \"rss_bytes\": %lld, "
                       "\"locked_bytes\": %lld, \"texture_bytes\": %lld,\n     \"realtime_command\": \"%s\", "
                       "\"realtime_rss_bytes\": %lld, \"realtime_vm_hwm_bytes\": %lld, \"threads\": %d,\n",
                       o.v.name.c_str(), o.command.c_str(), o.mlock ? "true" : "false", (long long)o.rss,
                       (long long)o.locked, (long long)o.texture, o.command_rt.c_str(), (long long)o.rss_rt,
                       (long long)o.hwm, o.threads);
      js += bench::fmt("     \"smaps\": {\"rss\": %lld, \"locked\": %lld, \"texture\": %lld, \"thread_stacks\": %lld, "
                       "\"thread_stack_count\": %d, \"main_stack\": %lld, \"ring\": %lld, \"flight_recorder\": %lld, "
                       "\"binary\": %lld, \"shared_libs\": %lld, \"heap\": %lld, \"other_anon\": %lld, "
                       "\"kernel\": %lld, \"libs\": {",
                       (long long)b.rss, (long long)b.locked, (long long)b.texture, (long long)b.stacks, b.stack_count,
                       (long long)b.main_stack, (long long)b.ring, (long long)b.flight, (long long)b.binary,
                       (long long)b.libs, (long long)b.heap, (long long)b.other_anon, (long long)b.kernel);
      bool first = true;
      for (const auto& [lib, r] : b.lib_rss) {
        js += bench::fmt("%s\"%s\": %lld", first ? "" : ", ", lib.c_str(), (long long)r);
        first = false;
      }
      js += std::string("}}}") + (i + 1 < out.size() ? ",\n" : "\n");
    }
    js += "  ]\n}\n";
    if (!json_path.empty()) bench::writeTextFile(json_path, js);

    if (!md_path.empty()) {
      std::string md = "Machine: " + bench::machineDescription() + "; measured " + bench::isoTimeNow() + ".\n\n";
      md += "RSS and locked: hapticd's own `--stats-json` (VmRSS / VmLck at the end of a `--lockstep` run). "
            "Breakdown: `/proc/<pid>/smaps` of the same command run in real time for 2 s (the sample with the largest "
            "total; its RSS in the “smaps total” column). Texture, ring and flight recorder are attributed by their "
            "known sizes (the kernel merges their anonymous mappings into one). hapticd locks memory with "
            "`MCL_ONFAULT` by default (pages are locked as they are first touched; VmLck counts the whole locked "
            "mappings, touched or not, so it can exceed VmRSS); `--mlock-eager` locks and faults in every mapped page "
            "at start. MB = 10⁶ bytes. Goal: ≤ 16 MB resident.\n\n";
      md += "| run | RSS (MB) | locked (MB) | goal | smaps total | texture | thread stacks | ring + flight recorder | "
            "hapticd binary | shared libraries | other heap + anonymous |\n";
      md += "|---|---|---|---|---|---|---|---|---|---|---|\n";
      for (const Outcome& o : out) {
        std::string flags;
        for (const auto& f : o.v.flags) flags += " " + f;
        const Breakdown& b = o.b;
        const std::string scene_name = o.v.scene.substr(o.v.scene.rfind('/') + 1);
        md += bench::fmt("| `%s`%s | %s | %s | %s | %s | %s | %s (%d × 512 KiB + main %s) | %s | %s | %s | %s |\n",
                         scene_name.c_str(), flags.c_str(), mb(o.rss).c_str(), mb(o.locked).c_str(),
                         o.rss <= 16000000 ? "met" : "**missed**", mb(b.rss).c_str(), mb(b.texture).c_str(),
                         mb(b.stacks + b.main_stack).c_str(), b.stack_count, mb(b.main_stack).c_str(),
                         mb(b.ring + b.flight).c_str(), mb(b.binary).c_str(), mb(b.libs).c_str(),
                         mb(b.heap + b.other_anon + b.kernel).c_str());
      }
      // The largest shared libraries in the first (default) run.
      std::vector<std::pair<std::int64_t, std::string>> libs;
      for (const auto& [lib, r] : out[0].b.lib_rss) libs.push_back({r, lib});
      std::sort(libs.rbegin(), libs.rend());
      md += "\nLargest shared libraries resident in the default (locked) run: ";
      for (std::size_t i = 0; i < libs.size() && i < 8; ++i) {
        md += bench::fmt("%s%s %s MB", i ? ", " : "", libs[i].second.c_str(), mb(libs[i].first).c_str());
      }
      md += bench::fmt(" (%zu files). TickRecord is %lld bytes: ring 1024 × = %s MB; the flight recorder keeps %lld "
                       "bytes of each tick: 2 × 1000 × = %s MB.\n",
                       libs.size(), (long long)tick_record, mb(kRingSlots * tick_record).c_str(),
                       (long long)flight_record, mb(2 * kFlightTicks * flight_record).c_str());
      bench::writeTextFile(md_path, md);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_memory: %s\n", e.what());
    return 1;
  }
  return 0;
}
