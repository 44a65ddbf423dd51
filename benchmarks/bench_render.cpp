// Part 1 of docs/benchmarks.md: the cost of one servo tick.
//
//  render/<texture>/<size>/<normal|relief>/<crease|nocrease>
//      ProxyRenderer::render alone, replaying the tip path a simulated PHANToM took through that
//      very configuration in lock-step (scenes/default.yaml: a diagonal stroke across bricks, then
//      a press; scenes/vvalley.yaml: a press into a valley floor, then a stroke across valleys),
//      trimmed to first..last contact. One benchmark iteration = one tick.
//  servo/<texture>/1024/relief/crease/<full|device|server|render>
//      the whole script, one repetition = one pass:
//        full    Servo::tick with the simulated device in lock-step (hapticd --lockstep's loop)
//        device  the simulated device alone: read() + write() of the commands the full run wrote
//        server  Servo::tick on a device that replays the full run's readings (render +
//                passivity + safety + bookkeeping: records, flight recorder, ring push)
//        render  ProxyRenderer::render alone on the same readings
//
// Reported per benchmark: Google Benchmark's median over repetitions of the mean time per tick,
// and, from three extra timed passes per repetition, the per-tick p50 / p99 (timer overhead
// subtracted; median over repetitions). Usage: bench_render [--csv FILE] [--md FILE] [--ridges sided|blend]
// [google-benchmark flags]; --ridges blend replays the same paths with issue 3's blended ridges.
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "rt/clock.hpp"
#include "benchmarks/bench_rig.hpp"
#include "server/scene_device.hpp"

namespace {

using namespace thx;

std::int64_t nowNs() { return rt::monotonicNowNs(); }

// Median cost of one nowNs() pair, subtracted from per-tick timings.
double timerOverheadNs() {
  std::vector<std::int64_t> d(2001);
  for (auto& x : d) {
    const std::int64_t a = nowNs();
    x = nowNs() - a;
  }
  std::nth_element(d.begin(), d.begin() + 1000, d.end());
  return double(d[1000]);
}

double quantile(std::vector<double>& v, double q) {
  if (v.empty()) return 0.0;
  const std::size_t k = std::min(v.size() - 1, std::size_t(q * double(v.size() - 1) + 0.5));
  std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(k), v.end());
  return v[k];
}

struct Fixture {
  std::string texture;  // bricks | vvalley
  int size = 0;
  bench::SceneTexture st;
};

struct Meta {
  std::string group, texture, reading, crease, part;
  int size = 0;
  std::size_t ticks = 0;
  double contact = 0.0;
};

std::map<std::string, Meta> g_meta;

// The fastest repetition: on a shared machine, the least disturbed one.
double minOf(const std::vector<double>& v) { return v.empty() ? 0.0 : *std::min_element(v.begin(), v.end()); }
double g_timer_ns = 0.0;

// --ridges blend: the renderer with issue 3's blended ridges (RendererConfig::sided_ridges =
// false) on the same recorded paths, for the cost of sided ridges (docs/benchmarks.md §1).
bool g_blend_ridges = false;
void applyRidges(bench::ServerRig& rig) {
  if (!g_blend_ridges) return;
  srv::RendererConfig c = rig.renderer().config();
  c.sided_ridges = false;
  rig.renderer().retarget(rig.renderer().surface(), c);
}

const char* kSceneFile(const std::string& texture) {
  return texture == "bricks" ? "/scenes/default.yaml" : "/scenes/vvalley.yaml";
}

void registerRender(const Fixture& fx, bool relief, bool crease) {
  auto rec = std::make_shared<bench::Recording>(bench::recordRun(fx.st.scene, fx.st.map(), relief, crease));
  // The contact window of the path (with the free-space ticks just around it).
  const std::size_t a = rec->first_contact, b = rec->last_contact;
  if (b < a) throw std::runtime_error("render benchmark: the scripted path never touched the surface");
  auto path = std::make_shared<std::vector<dev::DeviceState>>(rec->states.begin() + std::ptrdiff_t(a),
                                                              rec->states.begin() + std::ptrdiff_t(b + 1));
  std::size_t contact = 0;
  for (std::size_t k = a; k <= b; ++k) contact += rec->in_contact[k] ? 1 : 0;

  const std::string name = "render/" + fx.texture + "/" + std::to_string(fx.size) + "/" +
                           (relief ? "relief" : "normal") + "/" + (crease ? "crease" : "nocrease");
  g_meta[name] = Meta{"render", fx.texture, relief ? "relief" : "normal", crease ? "on" : "off", "render", fx.size,
                      path->size(), double(contact) / double(path->size())};
  const Fixture* f = &fx;
  benchmark::RegisterBenchmark(name.c_str(), [f, path, relief, crease](benchmark::State& state) {
    bench::ReplayDevice dummy(srv::deviceSpecFor(f->st.scene), *path);
    bench::ServerRig rig(f->st.scene, f->st.map(), relief, crease, dummy);
    applyRidges(rig);
    srv::ProxyRenderer& r = rig.renderer();
    const std::vector<dev::DeviceState>& p = *path;
    std::size_t k = 0;
    for (auto _ : state) {
      srv::RenderOutput out = r.render(p[k].p_world, p[k].v_world);
      benchmark::DoNotOptimize(out);
      if (++k == p.size()) {
        k = 0;
        r.reset();
      }
    }
    // Three more passes, each tick timed on its own.
    std::vector<double> t;
    t.reserve(3 * p.size());
    for (int pass = 0; pass < 3; ++pass) {
      r.reset();
      for (std::size_t i = 0; i < p.size(); ++i) {
        const std::int64_t t0 = nowNs();
        srv::RenderOutput out = r.render(p[i].p_world, p[i].v_world);
        benchmark::DoNotOptimize(out);
        t.push_back(std::max(0.0, double(nowNs() - t0) - g_timer_ns));
      }
    }
    state.counters["p50_ns"] = quantile(t, 0.5);
    state.counters["p99_ns"] = quantile(t, 0.99);
  })->Repetitions(5)->ReportAggregatesOnly(true)->Unit(benchmark::kNanosecond)->MinTime(0.3)->ComputeStatistics("min", minOf);
}

// Times Servo::tick; drains the publication ring outside the timing, as the publisher would.
void timeServoTicks(benchmark::State& state, bench::ServerRig& rig) {
  std::int64_t k = 0;
  for (auto _ : state) {
    const srv::TickRecord& r = rig.servo().tick();
    benchmark::DoNotOptimize(&r);
    if ((++k & 511) == 0) {
      state.PauseTiming();
      rig.drain();
      state.ResumeTiming();
    }
  }
  const srv::LatencyHistogram& h = rig.servo().computeHistogram();
  state.counters["compute_p50_ns"] = h.quantileUs(0.5) * 1e3;
  state.counters["compute_p99_ns"] = h.quantileUs(0.99) * 1e3;
}

void registerServo(const Fixture& fx) {
  const bool relief = true, crease = true;  // hapticd's defaults for these scenes
  auto rec = std::make_shared<bench::Recording>(bench::recordRun(fx.st.scene, fx.st.map(), relief, crease));
  const std::size_t n = rec->states.size();
  const std::string base = "servo/" + fx.texture + "/" + std::to_string(fx.size) + "/relief/crease/";
  const Fixture* f = &fx;
  auto meta = [&](const std::string& part) {
    g_meta[base + part] = Meta{"servo", fx.texture, "relief", "on", part, fx.size, n, rec->contactFraction()};
  };
  constexpr int kReps = 15;

  meta("full");
  benchmark::RegisterBenchmark((base + "full").c_str(), [f](benchmark::State& state) {
    dev::SimPhantom device(srv::simConfigFor(f->st.scene, true), srv::handScriptFor(f->st.scene));
    bench::ServerRig rig(f->st.scene, f->st.map(), true, true, device);
    applyRidges(rig);
    device.open();
    timeServoTicks(state, rig);
  })->Iterations(std::int64_t(n))->Repetitions(kReps)->ReportAggregatesOnly(true)->Unit(benchmark::kNanosecond)->ComputeStatistics("min", minOf);

  meta("device");
  benchmark::RegisterBenchmark((base + "device").c_str(), [f, rec](benchmark::State& state) {
    dev::SimPhantom device(srv::simConfigFor(f->st.scene, true), srv::handScriptFor(f->st.scene));
    device.open();
    std::size_t k = 0;
    for (auto _ : state) {
      const dev::DeviceState s = device.read();
      benchmark::DoNotOptimize(s);
      device.write(rec->commands[k]);
      k = k + 1 == rec->commands.size() ? 0 : k + 1;
    }
  })->Iterations(std::int64_t(n))->Repetitions(kReps)->ReportAggregatesOnly(true)->Unit(benchmark::kNanosecond)->ComputeStatistics("min", minOf);

  meta("server");
  benchmark::RegisterBenchmark((base + "server").c_str(), [f, rec](benchmark::State& state) {
    bench::ReplayDevice device(srv::deviceSpecFor(f->st.scene), rec->states);
    bench::ServerRig rig(f->st.scene, f->st.map(), true, true, device);
    applyRidges(rig);
    timeServoTicks(state, rig);
  })->Iterations(std::int64_t(n))->Repetitions(kReps)->ReportAggregatesOnly(true)->Unit(benchmark::kNanosecond)->ComputeStatistics("min", minOf);

  meta("render");
  benchmark::RegisterBenchmark((base + "render").c_str(), [f, rec](benchmark::State& state) {
    bench::ReplayDevice dummy(srv::deviceSpecFor(f->st.scene), rec->states);
    bench::ServerRig rig(f->st.scene, f->st.map(), true, true, dummy);
    applyRidges(rig);
    srv::ProxyRenderer& r = rig.renderer();
    const std::vector<dev::DeviceState>& p = rec->states;
    std::size_t k = 0;
    for (auto _ : state) {
      srv::RenderOutput out = r.render(p[k].p_world, p[k].v_world);
      benchmark::DoNotOptimize(out);
      k = k + 1 == p.size() ? 0 : k + 1;
    }
  })->Iterations(std::int64_t(n))->Repetitions(kReps)->ReportAggregatesOnly(true)->Unit(benchmark::kNanosecond)->ComputeStatistics("min", minOf);
}

// Console output as usual; the median aggregates are also kept for the CSV and the table.
class CollectingReporter : public benchmark::ConsoleReporter {
 public:
  explicit CollectingReporter(OutputOptions options) : ConsoleReporter(options) {}
  struct Row {
    std::string name;
    // Thread CPU time per tick: on a shared machine the wall clock also counts the time other
    // processes held the CPU (kept in the CSV as *_real_*).
    double median_ns = 0.0, min_ns = 0.0, cv = 0.0, median_real_ns = 0.0, min_real_ns = 0.0;
    std::map<std::string, double> counters;
  };
  void ReportRuns(const std::vector<Run>& runs) override {
    ConsoleReporter::ReportRuns(runs);
    for (const Run& r : runs) {
      if (r.run_type != Run::RT_Aggregate) continue;
      const std::string name = r.run_name.function_name;
      Row& row = rows_[name];
      row.name = name;
      if (r.aggregate_name == "median") {
        row.median_ns = r.GetAdjustedCPUTime();
        row.median_real_ns = r.GetAdjustedRealTime();
        for (const auto& [k, c] : r.counters) row.counters[k] = c.value;
      } else if (r.aggregate_name == "min") {
        row.min_ns = r.GetAdjustedCPUTime();
        row.min_real_ns = r.GetAdjustedRealTime();
      } else if (r.aggregate_name == "cv") {
        row.cv = r.GetAdjustedCPUTime();
      }
    }
  }
  const std::map<std::string, Row>& rows() const { return rows_; }

 private:
  std::map<std::string, Row> rows_;
};

std::string counter(const CollectingReporter::Row& r, const std::string& k) {
  const auto it = r.counters.find(k);
  return it == r.counters.end() ? "" : bench::fmt("%.0f", it->second);
}

void writeOutputs(const CollectingReporter& rep, const std::string& csv_path, const std::string& md_path) {
  std::string csv =
      "benchmark,group,texture,size,reading,crease,part,ticks,contact_fraction,median_cpu_ns_per_tick,"
      "min_cpu_ns_per_tick,cv,median_real_ns_per_tick,min_real_ns_per_tick,p50_ns,p99_ns,"
      "compute_p50_ns,compute_p99_ns\n";
  for (const auto& [name, r] : rep.rows()) {
    const Meta& m = g_meta[name];
    csv += bench::fmt("%s,%s,%s,%d,%s,%s,%s,%zu,%.3f,%.1f,%.1f,%.4f,%.1f,%.1f,", name.c_str(), m.group.c_str(),
                      m.texture.c_str(), m.size, m.reading.c_str(), m.crease.c_str(), m.part.c_str(), m.ticks,
                      m.contact, r.median_ns, r.min_ns, r.cv, r.median_real_ns, r.min_real_ns);
    csv += counter(r, "p50_ns") + "," + counter(r, "p99_ns") + "," + counter(r, "compute_p50_ns") + "," +
           counter(r, "compute_p99_ns") + "\n";
  }
  if (!csv_path.empty()) bench::writeTextFile(csv_path, csv);
  if (md_path.empty()) return;

  auto row = [&](const std::string& name) -> const CollectingReporter::Row* {
    const auto it = rep.rows().find(name);
    return it == rep.rows().end() ? nullptr : &it->second;
  };
  std::string md;
  md += "Machine: " + bench::machineDescription() + "; measured " + bench::isoTimeNow() + ".\n\n";
  md += "Per-tick `ProxyRenderer::render` on the contact part of a scripted path, ns. Mean = Google Benchmark's "
        "mean thread CPU time per tick, median of 5 repetitions (fastest repetition in brackets; wall-clock "
        "figures, which also count other processes' time slices on this shared VM, are in the CSV); p50 / p99 = "
        "wall-clock per-tick timing of "
        "three extra passes, " + bench::fmt("%.0f", g_timer_ns) + " ns of timer overhead subtracted (the clock's "
        "resolution on this VM is about 10 ns). Goal (issue 3): normal ≤ 1000 ns, relief ≤ 2000 ns median.\n\n";
  md += "| texture | size | reading | crease | ticks (in contact) | mean CPU ns (fastest) | p50 ns | p99 ns | goal |\n";
  md += "|---|---|---|---|---|---|---|---|---|\n";
  for (const char* texture : {"bricks", "vvalley"}) {
    for (int size : {512, 1024}) {
      for (const char* reading : {"normal", "relief"}) {
        for (const char* crease : {"nocrease", "crease"}) {
          const std::string name = bench::fmt("render/%s/%d/%s/%s", texture, size, reading, crease);
          const auto* r = row(name);
          if (!r) continue;
          const Meta& m = g_meta[name];
          const double goal = std::string(reading) == "normal" ? 1000.0 : 2000.0;
          const double p50 = r->counters.count("p50_ns") ? r->counters.at("p50_ns") : r->median_ns;
          const bool met = p50 <= goal && r->median_ns <= goal;
          md += bench::fmt("| %s | %d² | %s | %s | %zu (%.0f %%) | %.0f (%.0f) | %s | %s | %s |\n", texture, size,
                           reading, std::string(crease) == "crease" ? "on" : "off", m.ticks, 100.0 * m.contact,
                           r->median_ns, r->min_ns, counter(*r, "p50_ns").c_str(), counter(*r, "p99_ns").c_str(),
                           met ? bench::fmt("met (%.0f×)", goal / std::max(1.0, p50)).c_str() : "**missed**");
        }
      }
    }
  }
  md += "\nWhole servo tick in hapticd's configuration (1024² relief, crease on, passivity on, safety, flight "
        "recorder, ring push), one pass over the scene's whole script per repetition (free-space ticks included), "
        "thread CPU ns per tick: median of 15 repetitions (fastest in brackets). Shares are of the fastest full tick, from the "
        "fastest repetitions (the least disturbed on a shared machine).\n\n";
  md += "| texture | ticks (in contact) | part | ns/tick | share of the full tick |\n";
  md += "|---|---|---|---|---|\n";
  for (const char* texture : {"bricks", "vvalley"}) {
    const std::string base = bench::fmt("servo/%s/1024/relief/crease/", texture);
    const auto *full = row(base + "full"), *dev = row(base + "device"), *srv = row(base + "server"),
               *ren = row(base + "render");
    if (!full || !dev || !srv || !ren) continue;
    const Meta& m = g_meta[base + "full"];
    const std::string head = bench::fmt("%s 1024² | %zu (%.0f %%)", texture, m.ticks, 100.0 * m.contact);
    auto line = [&](const char* part, double med, double fast) {
      md += bench::fmt("| %s | %s | %.0f (%.0f) | %.0f %% |\n", head.c_str(), part, med, fast,
                       100.0 * fast / full->min_ns);
    };
    line("full `Servo::tick` with the simulated PHANToM in lock-step", full->median_ns, full->min_ns);
    line("device simulation alone (`SimPhantom::read` + `write`, 10 kHz integration)", dev->median_ns, dev->min_ns);
    line("server alone (`Servo::tick` on a replayed device)", srv->median_ns, srv->min_ns);
    line("… of which `ProxyRenderer::render`", ren->median_ns, ren->min_ns);
    line("… of which passivity + safety + bookkeeping (server − render)", srv->median_ns - ren->median_ns,
         srv->min_ns - ren->min_ns);
    md += bench::fmt("| %s | the servo's own compute histogram (render → safety, 0.1 µs bins) | p50 %s, p99 %s | |\n",
                     head.c_str(), counter(*full, "compute_p50_ns").c_str(), counter(*full, "compute_p99_ns").c_str());
  }
  bench::writeTextFile(md_path, md);
}

}  // namespace

int main(int argc, char** argv) {
  std::string csv_path, md_path;
  std::vector<char*> args;
  for (int i = 0; i < argc; ++i) {
    if ((std::strcmp(argv[i], "--csv") == 0 || std::strcmp(argv[i], "--md") == 0) && i + 1 < argc) {
      (std::strcmp(argv[i], "--csv") == 0 ? csv_path : md_path) = argv[i + 1];
      ++i;
    } else if (std::strcmp(argv[i], "--ridges") == 0 && i + 1 < argc) {
      g_blend_ridges = std::strcmp(argv[i + 1], "blend") == 0;
      if (!g_blend_ridges && std::strcmp(argv[i + 1], "sided") != 0) {
        std::fprintf(stderr, "bench_render: --ridges sided|blend\n");
        return 2;
      }
      ++i;
    } else {
      args.push_back(argv[i]);
    }
  }
  int n = int(args.size());
  benchmark::Initialize(&n, args.data());
  if (benchmark::ReportUnrecognizedArguments(n, args.data())) return 2;

  g_timer_ns = timerOverheadNs();
  std::vector<std::unique_ptr<Fixture>> fixtures;
  try {
    for (const char* texture : {"bricks", "vvalley"}) {
      for (int size : {512, 1024}) {
        std::fprintf(stderr, "bench_render: recording the %s %d² paths in lock-step\n", texture, size);
        auto fx = std::make_unique<Fixture>();
        fx->texture = texture;
        fx->size = size;
        fx->st = bench::loadSceneTexture(bench::sourceDir() + kSceneFile(texture), size);
        for (bool relief : {false, true}) {
          for (bool crease : {false, true}) registerRender(*fx, relief, crease);
        }
        if (size == 1024) registerServo(*fx);
        fixtures.push_back(std::move(fx));
      }
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_render: %s\n", e.what());
    return 1;
  }

  // Colour only on a terminal (run.sh logs to a pipe).
  CollectingReporter reporter(isatty(STDOUT_FILENO) ? benchmark::ConsoleReporter::OO_ColorTabular
                                                    : benchmark::ConsoleReporter::OO_Tabular);
  benchmark::RunSpecifiedBenchmarks(&reporter);
  benchmark::Shutdown();
  try {
    writeOutputs(reporter, csv_path, md_path);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_render: %s\n", e.what());
    return 1;
  }
  return 0;
}
