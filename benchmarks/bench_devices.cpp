// Several devices under one servo clock (issue 30; docs/hapticd.md "Several devices"): N simulated
// PHANToMs on the default scene's bricks, each behind its own servo wired as hapticd wires one
// (srv::servoRigConfigFor), serviced by one srv::ServoGroup at the scene's 1 kHz on a SCHED_FIFO
// thread, with cyclictest at the same period in the same window. Device i strokes the scene's
// diagonal shifted by i × 2 cm, back and forth, starting i × 0.2 s later. Per N: the group's tick
// compute (all devices) against one device's, its wake latency, missed periods against
// cyclictest's periods late by a whole period or more, each device's full-force share; and, in
// lock-step, the largest difference between a device's force in the group and alone. Measures
// only; nothing asserted.
//
// Usage: bench_devices --help (kHelp below).
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "base/cli_number.hpp"
#include "base/error.hpp"
#include "benchmarks/bench_help.hpp"
#include "benchmarks/bench_rig.hpp"
#include "benchmarks/bench_stamp.hpp"
#include "benchmarks/cyclictest_run.hpp"
#include "device/sim_phantom.hpp"
#include "rt/clock.hpp"
#include "scenes/scene_loader.hpp"
#include "scenes/scene_surface.hpp"
#include "server/realtime.hpp"
#include "server/scene_device.hpp"
#include "server/servo_group.hpp"
#include "server/servo_rig.hpp"

namespace {

using namespace thx;

constexpr const char* kHelp = R"(usage: bench_devices [--counts LIST] [--seconds S] [--lockstep-ticks N] [--cyclictest PATH]
                     [--workdir DIR] [--json F] [--md F]

Several simulated PHANToMs under one servo clock (srv::ServoGroup) on the default scene's bricks
(scenes/default.yaml), each behind its own servo wired as hapticd wires one, at the scene's 1 kHz
on a SCHED_FIFO thread (priority 80, memory locked), with cyclictest at the same period in the
same window. Device i strokes the scene's diagonal shifted by i x 2 cm, back and forth.

Per device count: the group's compute per tick (every device) p50 / p99 / max and its p99 over
the one-device run's; the wake latency p99 / max; missed periods; cyclictest's p99 / max and how
many of its periods were a whole period late or more; the lowest full-force share of the devices;
and in lock-step (a virtual clock) the largest |F_group - F_alone| of any device over the run.

  --counts LIST        device counts (default 1,2,4; at most 16)
  --seconds S          real-time run per count (default 10)
  --lockstep-ticks N   ticks of the lock-step comparison (default 6000)
  --cyclictest PATH    default: cyclictest on PATH ("none": not run)
  --workdir DIR        cyclictest's histogram files (default .)
  --json/--md F        results
)";

constexpr double kShiftM = 0.02;
constexpr double kStartStaggerS = 0.2;

dev::HandScript scriptOf(int i, double seconds) {
  const Eigen::Vector2d from(-0.06, -0.03 + kShiftM * (i - 1)), to(0.06, 0.03 + kShiftM * (i - 1));
  std::vector<dev::HandStep> steps;
  steps.push_back(dev::HandHold{0.1 + kStartStaggerS * i});
  const double stroke_s = (to - from).norm() / 0.05 + 0.6;  // the body, ramps, descent and ascent
  for (int k = 0; k < int(std::ceil(seconds / stroke_s)) + 1; ++k) {
    dev::HandStroke s;
    s.from_m = k % 2 ? to : from;
    s.to_m = k % 2 ? from : to;
    s.speed_m_per_s = 0.05;
    s.force_n = 1.0;
    steps.push_back(s);
  }
  return dev::HandScript(steps);
}

// N devices, their servos, one group on `clock`.
struct Devices {
  Devices(const scene::Scene& sc, const tex::TexturedSurface& surface, int n, double seconds, bool lockstep,
          rt::Clock& clock)
      : group(clock, std::int64_t(std::llround(1e9 / sc.rates.servo_hz))) {
    for (int i = 0; i < n; ++i) {
      devices.push_back(std::make_unique<dev::SimPhantom>(srv::simConfigFor(sc, lockstep), scriptOf(i, seconds)));
      rigs.push_back(std::make_unique<srv::ServoRig>(*devices.back(), surface, srv::servoRigConfigFor(sc)));
    }
    for (int i = 0; i < n; ++i) {
      devices[std::size_t(i)]->open();
      group.add(rigs[std::size_t(i)]->servo());
    }
  }
  std::vector<std::unique_ptr<dev::SimPhantom>> devices;
  std::vector<std::unique_ptr<srv::ServoRig>> rigs;
  srv::ServoGroup group;
};

// The largest |F_group - F_alone| of any device over `ticks` lock-step ticks.
double lockstepDifference(const scene::Scene& sc, const tex::TexturedSurface& surface, int n, int ticks) {
  rt::VirtualClock clock;
  Devices g(sc, surface, n, ticks * 1e-3, true, clock);
  g.group.start();
  std::vector<std::vector<Eigen::Vector3d>> grouped{std::size_t(n)};
  srv::TickRecord r;
  for (int k = 0; k < ticks; ++k) {
    g.group.tick();
    for (int i = 0; i < n; ++i)
      while (g.rigs[std::size_t(i)]->ring().pop(r)) grouped[std::size_t(i)].emplace_back(r.f_out[0], r.f_out[1], r.f_out[2]);
  }
  double worst = 0.0;
  for (int i = 0; i < n; ++i) {
    dev::SimPhantom device(srv::simConfigFor(sc, true), scriptOf(i, ticks * 1e-3));
    srv::ServoRig rig(device, surface, srv::servoRigConfigFor(sc));
    device.open();
    std::size_t k = 0;
    for (int t = 0; t < ticks; ++t) {
      rig.tick();
      while (rig.ring().pop(r)) {
        const Eigen::Vector3d f(r.f_out[0], r.f_out[1], r.f_out[2]);
        if (k < grouped[std::size_t(i)].size()) worst = std::max(worst, (f - grouped[std::size_t(i)][k]).norm());
        ++k;
      }
    }
  }
  return worst;
}

struct Row {
  int devices = 0;
  double compute_p50_us = 0, compute_p99_us = 0, compute_max_us = 0;
  double member_compute_p99_us = 0;  // the largest of the members' own p99s
  double wake_p99_us = 0, wake_max_us = 0;
  std::uint64_t ticks = 0, missed = 0;
  double min_full_force = 0;  // the lowest device's full-force share of its service periods
  std::uint64_t contact_ticks_min = 0;
  bool fifo = false;
  bench::Latency cyclictest;
  std::uint64_t cyclictest_late = 0;  // cyclictest periods late by >= one period
  double lockstep_max_df_n = 0;
};

Row runRealtime(const scene::Scene& sc, const tex::TexturedSurface& surface, int n, int seconds,
                const std::string& cyclictest, const std::string& workdir) {
  Row row;
  row.devices = n;
  rt::MonotonicClock clock;
  Devices g(sc, surface, n, seconds, false, clock);
  const int period_us = int(std::lround(1e6 / sc.rates.servo_hz));

  std::optional<bench::Job> job;
  std::optional<int> ended;
  bool cyclictest_fifo = false;
  if (cyclictest != "none") {
    job = bench::startCyclictest(cyclictest, seconds, workdir, "devices" + std::to_string(n), period_us);
    cyclictest_fifo = bench::sawFifo(job->pid, ended);
  }

  std::atomic<bool> done{false};
  std::thread drain([&] {  // the publisher's part: every ring emptied every 0.5 ms
    srv::TickRecord r;
    while (!done.load()) {
      for (auto& rig : g.rigs)
        while (rig->ring().pop(r)) {
        }
      std::this_thread::sleep_for(std::chrono::microseconds(500));
    }
  });
  std::thread servo([&] {
    srv::RealtimeOptions o;
    const srv::RealtimeReport rep = srv::makeThreadRealtime(o);
    row.fifo = rep.fifo;
    const std::int64_t stop_tick = std::int64_t(seconds) * std::int64_t(sc.rates.servo_hz);
    g.group.start();
    bool stopping = false;
    while (!g.group.finished()) {
      const srv::ServoGroup::Tick& t = g.group.tick();
      if (!stopping && t.timing.tick >= stop_tick) {
        g.group.requestShutdown();
        stopping = true;
      }
    }
  });
  servo.join();
  done.store(true);
  drain.join();

  const srv::ServoGroup& gr = g.group;
  row.compute_p50_us = gr.computeHistogram().quantileUs(0.5);
  row.compute_p99_us = gr.computeHistogram().quantileUs(0.99);
  row.compute_max_us = double(gr.computeHistogram().maxNs()) * 1e-3;
  row.wake_p99_us = gr.wakeHistogram().quantileUs(0.99);
  row.wake_max_us = double(gr.wakeHistogram().maxNs()) * 1e-3;
  row.min_full_force = 1.0;
  row.contact_ticks_min = ~std::uint64_t(0);
  for (int i = 0; i < n; ++i) {
    const srv::Servo& s = gr.member(i);
    row.member_compute_p99_us = std::max(row.member_compute_p99_us, s.computeHistogram().quantileUs(0.99));
    const srv::ServoCounters& c = s.counters();
    const double periods = double(c.service_ticks + c.service_missed_ticks);
    row.min_full_force = std::min(row.min_full_force, periods > 0 ? double(c.full_force_ticks) / periods : 0.0);
    row.contact_ticks_min = std::min(row.contact_ticks_min, c.contact_ticks);
    if (i == 0) row.ticks = c.ticks, row.missed = c.missed_ticks;
  }
  if (job) {
    row.cyclictest = bench::finishCyclictest(*job, "devices" + std::to_string(n), cyclictest_fifo, ended);
    row.cyclictest_late = bench::countAtLeastUs(row.cyclictest, period_us);
  }
  return row;
}

std::string json(const std::vector<Row>& rows, int seconds) {
  std::string js = "{\n  \"benchmark\": \"several devices under one servo clock (srv::ServoGroup), default scene\",\n";
  js += bench::fmt("  \"time\": \"%s\", \"machine\": \"%s\", \"build_type\": \"%s\", \"seconds\": %d,\n",
                   bench::isoTimeNow().c_str(), bench::machineSummary().c_str(), bench::buildType(), seconds);
  js += "  \"rows\": [\n";
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const Row& r = rows[k];
    js += bench::fmt(
        "    {\"devices\": %d, \"servo_fifo\": %s, \"ticks\": %llu, \"missed\": %llu, "
        "\"compute_us\": {\"p50\": %.1f, \"p99\": %.1f, \"max\": %.1f}, \"member_compute_p99_us\": %.1f, "
        "\"wake_us\": {\"p99\": %.1f, \"max\": %.1f}, \"min_full_force\": %.5f, \"min_contact_ticks\": %llu, "
        "\"cyclictest\": {\"ok\": %s, \"sched_fifo\": %s, \"p99_us\": %.0f, \"max_us\": %.0f, \"late_periods\": %llu}, "
        "\"lockstep_max_df_n\": %.3g}%s\n",
        r.devices, r.fifo ? "true" : "false", (unsigned long long)r.ticks, (unsigned long long)r.missed,
        r.compute_p50_us, r.compute_p99_us, r.compute_max_us, r.member_compute_p99_us, r.wake_p99_us, r.wake_max_us,
        r.min_full_force, (unsigned long long)r.contact_ticks_min, r.cyclictest.ok ? "true" : "false",
        r.cyclictest.fifo ? "true" : "false", r.cyclictest.p99_us, r.cyclictest.max_us,
        (unsigned long long)r.cyclictest_late, r.lockstep_max_df_n, k + 1 < rows.size() ? "," : "");
  }
  js += "  ]\n}\n";
  return js;
}

std::string markdown(const std::vector<Row>& rows, int seconds) {
  std::string md = bench::fmt("%s, %s build, %d s per row.\n\n", bench::machineSummary().c_str(), bench::buildType(), seconds);
  md += "| devices | group compute p50 / p99 / max µs | p99 / one device's | wake p99 / max µs | missed periods | "
        "cyclictest p99 / max µs, periods ≥ 1 ms late | lowest full force | lock-step max \\|ΔF\\| N |\n";
  md += "|---|---|---|---|---|---|---|---|\n";
  const double one = rows.empty() ? 0.0 : rows.front().devices == 1 ? rows.front().compute_p99_us : 0.0;
  for (const Row& r : rows) {
    const std::string ratio = one > 0 ? bench::fmt("%.2f", r.compute_p99_us / one) : "n/a";
    const std::string ct = r.cyclictest.ok ? bench::fmt("%.0f / %.0f, %llu", r.cyclictest.p99_us, r.cyclictest.max_us,
                                                        (unsigned long long)r.cyclictest_late)
                                           : "not run";
    md += bench::fmt("| %d | %.1f / %.1f / %.1f | %s | %.1f / %.1f | %llu of %llu | %s | %.2f %% | %.2g |\n", r.devices,
                     r.compute_p50_us, r.compute_p99_us, r.compute_max_us, ratio.c_str(), r.wake_p99_us, r.wake_max_us,
                     (unsigned long long)r.missed, (unsigned long long)(r.ticks + r.missed), ct.c_str(),
                     100.0 * r.min_full_force, r.lockstep_max_df_n);
  }
  return md;
}

int run(int argc, char** argv) {
  std::vector<int> counts{1, 2, 4};
  int seconds = 10, lockstep_ticks = 6000;
  std::string cyclictest = "cyclictest", workdir = ".", json_path, md_path;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (i + 1 >= argc) throw UsageError(a + " needs a value (see --help)");
    const std::string v = argv[++i];
    if (a == "--counts") counts = cli::parseIntegerList(a, v, 1, srv::ServoGroup::kMaxDevices);
    else if (a == "--seconds") seconds = int(cli::parseInteger(a, v, 1, 3600));
    else if (a == "--lockstep-ticks") lockstep_ticks = int(cli::parseInteger(a, v, 1, 10'000'000));
    else if (a == "--cyclictest") cyclictest = v;
    else if (a == "--workdir") workdir = v;
    else if (a == "--json") json_path = v;
    else if (a == "--md") md_path = v;
    else throw UsageError("unknown option " + a + " (see --help)");
  }
  const scene::Scene sc = scene::loadScene(bench::sourceDir() + "/scenes/default.yaml");
  const scene::SceneSurface built = scene::buildSceneSurface(sc);
  srv::prepareProcessForLockedMemory();

  std::vector<Row> rows;
  for (const int n : counts) {
    std::fprintf(stderr, "bench_devices: %d device(s): lock-step comparison over %d ticks ...\n", n, lockstep_ticks);
    const double df = lockstepDifference(sc, built.surface, n, lockstep_ticks);
    std::fprintf(stderr, "bench_devices: %d device(s): %d s in real time ...\n", n, seconds);
    Row r = runRealtime(sc, built.surface, n, seconds, cyclictest, workdir);
    r.lockstep_max_df_n = df;
    rows.push_back(r);
  }
  const std::string md = markdown(rows, seconds);
  std::fputs(md.c_str(), stdout);
  if (!json_path.empty()) bench::writeTextFile(json_path, json(rows, seconds));
  if (!md_path.empty()) bench::writeTextFile(md_path, md);
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return bench::benchMain(argc, argv, kHelp, "bench_devices", run); }
