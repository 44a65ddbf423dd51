// The texture's force against the servo rate (issue 30; docs/hapticd.md "Servo rates above 1 kHz").
// The default scene's bricks (scenes/default.yaml, built as hapticd builds them) under the plane
// renderer hapticd runs (crease handling, sided ridges, the scene's 600 N/m and 1 N s/m), fed a
// kinematic pen: down from 1 mm above the bricks to 0.5 mm into them, then the scene's diagonal
// stroke across head and bed joints at a steady speed. At servo rate R the renderer runs at the
// ticks k / R and the device holds each tick's force until the next (zero-order hold). The truth
// is the same renderer at 200 kHz with the recovery rule off: the texture's force as the renderer
// defines it, sampled finely. Measures only; nothing asserted.
//
// Usage: bench_rate_texture --help (kHelp below).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "base/cli_number.hpp"
#include "base/error.hpp"
#include "benchmarks/bench_help.hpp"
#include "benchmarks/bench_rig.hpp"
#include "benchmarks/bench_stamp.hpp"
#include "scenes/scene_loader.hpp"
#include "scenes/scene_surface.hpp"
#include "server/proxy_renderer.hpp"
#include "tools/report/plot.hpp"

namespace {

using namespace thx;

constexpr const char* kHelp = R"(usage: bench_rate_texture [--rates LIST] [--speeds LIST] [--json F] [--csv F] [--md F] [--png F]

The texture's force against the servo rate: the default scene's bricks (scenes/default.yaml) under
hapticd's plane renderer (crease handling, 600 N/m, 1 N s/m), a kinematic pen 0.5 mm into the
bricks stroking the scene's diagonal across head and bed joints. At each servo rate the device
holds each tick's force until the next; the error is against the same renderer at 200 kHz with
the recovery rule off, over the stroke: RMS |F_held - F_true| over RMS |F_true| (all of the
force, and its component along the surface: the texture's push), and the largest |error|.
Three recovery rules: the shipped one (10 ticks, whatever the rate), 10 ms (10 ticks at 1 kHz,
40 at 4 kHz) and none. Also the renderer's mean time per tick and what that costs per second.

  --rates LIST    servo rates in Hz, each dividing 200000 (default 500,1000,2000,4000,8000)
  --speeds LIST   stroke speeds in mm/s (default 50,200: the scene's, and a fast stroke)
  --json/--csv/--md/--png F   results (the plot: error against rate, log-log)
)";

constexpr double kTruthHz = 200000.0;
constexpr double kDescentS = 0.05;      // 1 mm above to 0.5 mm into the bricks
constexpr double kAboveM = 1e-3, kIntoM = 5e-4;
const Eigen::Vector2d kFrom(-0.06, -0.03), kTo(0.06, 0.03);  // the scene's stroke

enum class Recovery { Shipped, TenMs, Off };
const char* recoveryName(Recovery r) {
  switch (r) {
    case Recovery::Shipped: return "10 ticks (shipped)";
    case Recovery::TenMs: return "10 ms";
    case Recovery::Off: return "off";
  }
  return "";
}

// The pen's path: straight down, then the stroke.
struct Path {
  double speed_m_per_s;
  double strokeS() const { return (kTo - kFrom).norm() / speed_m_per_s; }
  double endS() const { return kDescentS + strokeS(); }
  Eigen::Vector3d at(double t) const {
    if (t < kDescentS) return {kFrom.x(), kFrom.y(), kAboveM - (kAboveM + kIntoM) * t / kDescentS};
    const double a = std::min(1.0, (t - kDescentS) / strokeS());
    const Eigen::Vector2d xy = kFrom + a * (kTo - kFrom);
    return {xy.x(), xy.y(), -kIntoM};
  }
  Eigen::Vector3d velocity(double t) const {
    if (t < kDescentS) return {0.0, 0.0, -(kAboveM + kIntoM) / kDescentS};
    return speed_m_per_s * Eigen::Vector3d((kTo - kFrom).x(), (kTo - kFrom).y(), 0.0) / (kTo - kFrom).norm();
  }
};

// The forces of one run at `rate_hz`, one per tick, and the mean time of a render() call.
struct Run {
  std::vector<Eigen::Vector3d> forces;
  double ns_per_tick = 0.0;
};

Run render(const tex::TexturedSurface& surface, const srv::RendererConfig& config, const Path& path, double rate_hz) {
  srv::ProxyRenderer renderer(surface, config);
  Run run;
  const auto ticks = std::size_t(std::floor(path.endS() * rate_hz)) + 1;
  run.forces.reserve(ticks);
  const auto t0 = std::chrono::steady_clock::now();
  for (std::size_t k = 0; k < ticks; ++k) {
    const double t = double(k) / rate_hz;
    run.forces.push_back(renderer.render(surface.toWorld(path.at(t)), surface.mapping().directionToWorld(path.velocity(t)))
                             .force_world);
  }
  const auto t1 = std::chrono::steady_clock::now();
  run.ns_per_tick = std::chrono::duration<double, std::nano>(t1 - t0).count() / double(ticks);
  return run;
}

struct Row {
  int rate_hz = 0;
  double speed_mm_per_s = 0;
  Recovery recovery = Recovery::Shipped;
  double rel_rms = 0, rel_rms_tangent = 0, max_error_n = 0;
  double ns_per_tick = 0;
};

// The held forces of `run` against the truth over the stroke (from the end of the descent).
Row compare(const Run& truth, const Run& run, int rate_hz, const tex::TexturedSurface& surface) {
  const Eigen::Vector3d n = surface.mapping().geometricNormalWorld();
  const auto first = std::size_t(std::ceil(kDescentS * kTruthHz));
  const auto per_tick = std::size_t(kTruthHz) / std::size_t(rate_hz);
  double e2 = 0, f2 = 0, et2 = 0, ft2 = 0, emax = 0;
  for (std::size_t j = first; j < truth.forces.size(); ++j) {
    const std::size_t k = std::min(run.forces.size() - 1, j / per_tick);
    const Eigen::Vector3d f = truth.forces[j], e = run.forces[k] - f;
    const Eigen::Vector3d ft = f - f.dot(n) * n, et = e - e.dot(n) * n;
    e2 += e.squaredNorm(), f2 += f.squaredNorm(), et2 += et.squaredNorm(), ft2 += ft.squaredNorm();
    emax = std::max(emax, e.norm());
  }
  Row r;
  r.rate_hz = rate_hz;
  r.rel_rms = f2 > 0 ? std::sqrt(e2 / f2) : 0.0;
  r.rel_rms_tangent = ft2 > 0 ? std::sqrt(et2 / ft2) : 0.0;
  r.max_error_n = emax;
  r.ns_per_tick = run.ns_per_tick;
  return r;
}

std::string pct(double v) { return v >= 0.001 ? bench::fmt("%.2f %%", 100 * v) : bench::fmt("%.2g %%", 100 * v); }

void writePlot(const std::string& path, const std::vector<Row>& rows, const std::vector<int>& speeds) {
  bench::PlotPanel panel;
  panel.title = "bricks, 0.5 mm deep: force error against the servo rate";
  panel.x_label = "servo rate (Hz)";
  panel.y_label = "RMS error / RMS force";
  panel.x_min = 300, panel.x_max = 12000, panel.y_min = 1e-3, panel.y_max = 1.0;
  const bench::Rgb colours[] = {{200, 60, 40}, {40, 110, 200}, {40, 150, 60}};
  const bench::Marker markers[] = {bench::Marker::Circle, bench::Marker::Square, bench::Marker::Triangle};
  for (std::size_t s = 0; s < speeds.size(); ++s)
    for (const Recovery rec : {Recovery::Shipped, Recovery::TenMs, Recovery::Off}) {
      bench::PlotSeries series;
      series.label = bench::fmt("%d mm/s, recovery %s", speeds[s],
                                rec == Recovery::Shipped ? "10 ticks" : rec == Recovery::TenMs ? "10 ms" : "off");
      series.color = colours[int(rec)];
      series.marker = markers[s % 3];
      series.filled = s == 0;
      for (const Row& r : rows)
        if (r.speed_mm_per_s == speeds[s] && r.recovery == rec) {
          series.x.push_back(r.rate_hz);
          series.y.push_back(std::max(r.rel_rms, 1e-3));
        }
      panel.series.push_back(series);
    }
  bench::writePlotPng(path, {panel}, "bench_rate_texture: zero-order-held force against the renderer at 200 kHz");
}

int run(int argc, char** argv) {
  std::vector<int> rates{500, 1000, 2000, 4000, 8000}, speeds{50, 200};
  std::string json, csv, md, png;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (i + 1 >= argc) throw UsageError(a + " needs a value (see --help)");
    const std::string v = argv[++i];
    if (a == "--rates") rates = cli::parseIntegerList(a, v, 100, 100000);
    else if (a == "--speeds") speeds = cli::parseIntegerList(a, v, 1, 2000);
    else if (a == "--json") json = v;
    else if (a == "--csv") csv = v;
    else if (a == "--md") md = v;
    else if (a == "--png") png = v;
    else throw UsageError("unknown option " + a + " (see --help)");
  }
  for (int r : rates)
    if (200000 % r != 0) throw UsageError(bench::fmt("--rates: %d Hz does not divide the truth's 200 kHz", r));

  const scene::Scene sc = scene::loadScene(bench::sourceDir() + "/scenes/default.yaml");
  const scene::SceneSurface built = scene::buildSceneSurface(sc);
  srv::RendererConfig config;
  config.stiffness_n_per_m = sc.device.stiffnessNPerM();
  config.damping_ns_per_m = sc.device.damping_ns_per_m;
  const int shipped_recovery = config.recovery_ticks;

  std::vector<Row> rows;
  for (const int speed : speeds) {
    const Path path{speed * 1e-3};
    srv::RendererConfig truth_config = config;
    truth_config.recovery_ticks = 0;
    std::fprintf(stderr, "bench_rate_texture: %d mm/s, the truth at 200 kHz ...\n", speed);
    const Run truth = render(built.surface, truth_config, path, kTruthHz);
    for (const int rate : rates)
      for (const Recovery rec : {Recovery::Shipped, Recovery::TenMs, Recovery::Off}) {
        srv::RendererConfig c = config;
        c.recovery_ticks = rec == Recovery::Shipped ? shipped_recovery
                           : rec == Recovery::TenMs ? int(std::lround(shipped_recovery * rate / 1000.0))
                                                    : 0;
        Row r = compare(truth, render(built.surface, c, path, rate), rate, built.surface);
        r.speed_mm_per_s = speed;
        r.recovery = rec;
        rows.push_back(r);
      }
  }

  const std::string stamp =
      bench::fmt("%s, %s build, %s", bench::isoNow().c_str(), bench::buildType(), bench::machineSummary().c_str());
  if (!csv.empty()) {
    std::string c = "speed_mm_per_s,rate_hz,recovery,rel_rms_error,rel_rms_error_along_surface,max_error_n,ns_per_tick,"
                    "cpu_ms_per_s\n";
    for (const Row& r : rows)
      c += bench::fmt("%.0f,%d,%s,%.6f,%.6f,%.5f,%.1f,%.3f\n", r.speed_mm_per_s, r.rate_hz, recoveryName(r.recovery),
                      r.rel_rms, r.rel_rms_tangent, r.max_error_n, r.ns_per_tick, r.ns_per_tick * r.rate_hz * 1e-6);
    bench::writeTextFile(csv, c);
  }
  if (!json.empty()) {
    std::string j = "{\"benchmark\": \"the texture's force against the servo rate\", \"stamp\": \"" + stamp +
                    "\", \"scene\": \"scenes/default.yaml\", \"truth_hz\": 200000, \"rows\": [";
    for (std::size_t k = 0; k < rows.size(); ++k) {
      const Row& r = rows[k];
      j += bench::fmt("%s{\"speed_mm_per_s\": %.0f, \"rate_hz\": %d, \"recovery\": \"%s\", \"rel_rms_error\": %.6f, "
                      "\"rel_rms_error_along_surface\": %.6f, \"max_error_n\": %.5f, \"ns_per_tick\": %.1f}",
                      k ? ", " : "", r.speed_mm_per_s, r.rate_hz, recoveryName(r.recovery), r.rel_rms, r.rel_rms_tangent,
                      r.max_error_n, r.ns_per_tick);
    }
    bench::writeTextFile(json, j + "]}\n");
  }
  if (!md.empty()) {
    std::string t = "Measured " + stamp +
                    ". The default scene's bricks, 0.5 mm into them, the scene's diagonal stroke; error of the "
                    "held force against the renderer at 200 kHz without the recovery rule (RMS over RMS of the "
                    "force; along the surface: the same of the force's component along the plane). Time: mean "
                    "render() per tick, and per second of servo at that rate.\n\n"
                    "| speed | servo rate | recovery | error | error along the surface | largest error | time per tick | "
                    "per second |\n|---:|---:|---|---:|---:|---:|---:|---:|\n";
    for (const Row& r : rows)
      t += bench::fmt("| %.0f mm/s | %d Hz | %s | %s | %s | %.3f N | %.0f ns | %.2f ms |\n", r.speed_mm_per_s, r.rate_hz,
                      recoveryName(r.recovery), pct(r.rel_rms).c_str(), pct(r.rel_rms_tangent).c_str(), r.max_error_n,
                      r.ns_per_tick, r.ns_per_tick * r.rate_hz * 1e-6);
    bench::writeTextFile(md, t);
  }
  if (!png.empty()) writePlot(png, rows, speeds);
  for (const Row& r : rows)
    std::printf("%4.0f mm/s %5d Hz recovery %-18s error %8s, along %8s, max %.3f N, %.0f ns/tick\n", r.speed_mm_per_s,
                r.rate_hz, recoveryName(r.recovery), pct(r.rel_rms).c_str(), pct(r.rel_rms_tangent).c_str(),
                r.max_error_n, r.ns_per_tick);
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return bench::benchMain(argc, argv, kHelp, "bench_rate_texture", run); }
