// Objects rocking on an untextured curved mesh (issue 29; docs/physics.md "Boxes and rods on a
// smooth curved mesh"): a block on a cylinder, a capsule and a cylinder rolling in a pipe
// (tests/physics/rocking_on_curve_scene.hpp), their swing's period against the exact rolling
// answer, by the mesh's tessellation and the smooth chart's grid, beside Bullet's flat triangles;
// with the cost of a step. Measures only; nothing asserted (tests/physics/test_objects_on_smooth_mesh.cpp
// holds the behaviour).
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "base/cli_number.hpp"
#include "base/error.hpp"
#include "benchmarks/bench_help.hpp"
#include "benchmarks/bench_rig.hpp"
#include "benchmarks/bench_stamp.hpp"
#include "tools/report/plot.hpp"
#include "tests/physics/rocking_on_curve_scene.hpp"

namespace {

using namespace thx;
using namespace thx::phys::test::rocking_on_curve;

constexpr const char* kHelp = R"(usage: bench_rocking_on_curve [--segments N,N,...] [--grids N,N,...] [--steps MS,...] [--seconds S] [--json F] [--csv F] [--md F] [--png F]

Boxes and rods on an untextured curved mesh, met on its smooth chart (the surface the mesh stands
for, sampled on a grid over the object's underside) and on Bullet's flat triangles:
  block     2 x 2 x 1 cm, 30 g, on top of a horizontal cylinder of radius 5 cm, rocking across it;
  capsule   radius 6 mm, 4 cm between its caps' centres, 30 g, lying inside a pipe of radius 5 cm;
  cylinder  the same as a cylinder, 4 cm long.
Each is released from rest rolled 0.05 rad from the bottom of its swing (friction 1, 1 ms steps
unless --steps) and run S seconds; its period is read from the swing angle's upward zero
crossings and compared with the rolling equations (without slipping) integrated at 0.1 ms. The
amplitude kept is the last half swing's over the first's (1 without losses).

  --segments LIST  the cylinders' segments around (default 32,64,128,256), each at a grid of 16
  --grids LIST     the smooth chart's intervals along the object's longer side (8 at least), at
                   128 segments (default 8,16,32,64)
  --steps LIST     step lengths in ms besides 1, at 128 segments and a grid of 16 (default 0.25)
  --seconds S      per run (default 2)
  --json/--csv/--md F   results
  --png F          the period's error and the step's cost against the segments, smooth chart
                   against Bullet's triangles (a run without a swing is left out)
)";

constexpr Rocker kRockers[] = {Rocker::Block, Rocker::Capsule, Rocker::Cylinder};
const char* const kRockerNames[] = {"block on a cylinder", "capsule in a pipe", "cylinder in a pipe"};
constexpr double kRelease = 0.05;
constexpr int kDefaultGrid = 16;

struct Row {
  int rocker = 0;
  bool smooth = true;
  int segments = 0, grid = 0;
  double dt_ms = 1.0;
  double exact_s = 0, period_s = 0, error_pct = 0, kept = 0, us_per_step = 0;
  int swings = 0;
};

const char* contactName(const Row& r) { return r.smooth ? "smooth chart" : "Bullet's triangles"; }

Row measure(int rocker, bool smooth, int segments, int grid, double seconds, double dt_ms = 1.0) {
  std::fprintf(stderr, "bench_rocking_on_curve: %s, %s, %d segments, grid %d, %g ms steps ...\n", kRockerNames[rocker],
               smooth ? "smooth chart" : "triangles", segments, grid, dt_ms);
  RockingScene scene(kRockers[rocker], smooth ? Contact::SmoothChart : Contact::Triangles, segments, kRelease, grid,
                     1e-3 * dt_ms);
  Row row;
  row.rocker = rocker, row.smooth = smooth, row.segments = segments, row.grid = smooth ? grid : 0, row.dt_ms = dt_ms;
  row.exact_s = kRockers[rocker] == Rocker::Block ? blockPeriod(kRelease) : rodPeriod(kRelease, scene.rodInertiaPerMass());
  const Swing s = scene.run(seconds);
  row.period_s = s.period_s, row.swings = s.swings, row.kept = s.amplitude_kept, row.us_per_step = s.us_per_step;
  row.error_pct = s.swings > 0 ? 100.0 * (s.period_s / row.exact_s - 1.0) : std::nan("");
  return row;
}

std::string periodCell(const Row& r) {
  return r.swings > 0 ? bench::fmt("%.4f s | %+.2f %%", r.period_s, r.error_pct) : std::string("no swing | —");
}

// The rows at the default grid and 1 ms steps, by segments: error and cost, each object on its
// smooth chart (filled) and on Bullet's triangles (hollow).
void writePlot(const std::string& path, const std::vector<Row>& rows, const std::string& stamp) {
  bench::PlotPanel error, cost;
  error.title = "Swing period against the rolling answer", error.x_label = "segments", error.y_label = "|error| %";
  cost.title = "Cost of a step", cost.x_label = "segments", cost.y_label = "microseconds per step";
  const bench::Rgb colors[] = {{200, 60, 40}, {60, 120, 200}, {40, 150, 70}};
  const bench::Marker markers[] = {bench::Marker::Square, bench::Marker::Circle, bench::Marker::Triangle};
  double e_min = 1e9, e_max = 0, c_min = 1e9, c_max = 0, x_min = 1e9, x_max = 0;
  for (int rocker = 0; rocker < 3; ++rocker) {
    for (bool smooth : {true, false}) {
      bench::PlotSeries e;
      e.label = std::string(kRockerNames[rocker]) + (smooth ? ", smooth chart" : ", Bullet's triangles");
      e.color = colors[rocker], e.marker = markers[rocker], e.filled = smooth;
      bench::PlotSeries c = e;
      for (const Row& r : rows) {
        if (r.rocker != rocker || r.smooth != smooth || r.dt_ms != 1.0 || (smooth && r.grid != kDefaultGrid)) continue;
        const double x = r.segments;
        x_min = std::min(x_min, x), x_max = std::max(x_max, x);
        c.x.push_back(x), c.y.push_back(r.us_per_step);
        c_min = std::min(c_min, r.us_per_step), c_max = std::max(c_max, r.us_per_step);
        if (r.swings <= 0) continue;
        const double err = std::max(1e-3, std::fabs(r.error_pct));  // log axis: zero at its floor
        e.x.push_back(x), e.y.push_back(err);
        e_min = std::min(e_min, err), e_max = std::max(e_max, err);
      }
      error.series.push_back(e);
      cost.series.push_back(c);
    }
  }
  for (bench::PlotPanel* p : {&error, &cost}) p->x_min = x_min / 1.5, p->x_max = x_max * 1.5;
  error.y_min = e_min / 2, error.y_max = e_max * 2;
  cost.y_min = c_min / 1.5, cost.y_max = c_max * 1.5;
  bench::writePlotPng(path, {error, cost},
                      "bench_rocking_on_curve: boxes and rods on untextured cylinders, grid 16, 1 ms (" + stamp + ")",
                      560, 480);
}

int run(int argc, char** argv) {
  std::vector<int> segments{32, 64, 128, 256}, grids{8, 16, 32, 64};
  std::vector<double> steps{0.25};
  double seconds = 2.0;
  std::string json, csv, md, png;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (i + 1 >= argc) throw UsageError(a + " needs a value (see --help)");
    const std::string v = argv[++i];
    if (a == "--segments") segments = cli::parseIntegerList(a, v, 8, 4096);
    else if (a == "--grids") grids = cli::parseIntegerList(a, v, 8, 512);
    else if (a == "--steps") steps = cli::parseNumberList(a, v, {0.01, 10.0, false, "ms"});
    else if (a == "--seconds") seconds = cli::parseNumber(a, v, {0.2, 60.0, false, "s"});
    else if (a == "--json") json = v;
    else if (a == "--csv") csv = v;
    else if (a == "--md") md = v;
    else if (a == "--png") png = v;
    else throw UsageError("unknown option " + a + " (see --help)");
  }
  std::vector<Row> rows;
  for (int r = 0; r < 3; ++r) {
    for (int n : segments) {
      rows.push_back(measure(r, true, n, kDefaultGrid, seconds));
      rows.push_back(measure(r, false, n, 0, seconds));
    }
    for (int g : grids)
      if (g != kDefaultGrid) rows.push_back(measure(r, true, 128, g, seconds));
    for (double dt : steps)
      if (dt != 1.0) rows.push_back(measure(r, true, 128, kDefaultGrid, seconds, dt));
  }
  const std::string stamp = bench::fmt("%s, %s build, %s", bench::isoNow().c_str(), bench::buildType(),
                                       bench::machineSummary().c_str());
  if (!csv.empty()) {
    std::string c = "rocker,contact,segments,grid,dt_ms,exact_s,period_s,error_pct,swings,amplitude_kept,us_per_step\n";
    for (const Row& r : rows)
      c += bench::fmt("%s,%s,%d,%d,%g,%.5f,%.5f,%.3f,%d,%.4f,%.2f\n", kRockerNames[r.rocker], contactName(r), r.segments,
                      r.grid, r.dt_ms, r.exact_s, r.period_s, r.error_pct, r.swings, r.kept, r.us_per_step);
    bench::writeTextFile(csv, c);
  }
  if (!json.empty()) {
    std::string j = bench::fmt("{\"stamp\": \"%s\", \"rows\": [", stamp.c_str());
    for (std::size_t k = 0; k < rows.size(); ++k) {
      const Row& r = rows[k];
      const std::string error = r.swings > 0 ? bench::fmt("%.4f", r.error_pct) : std::string("null");
      j += bench::fmt("%s{\"rocker\": \"%s\", \"contact\": \"%s\", \"segments\": %d, \"grid\": %d, \"dt_ms\": %g, "
                      "\"exact_s\": %.6f, \"period_s\": %.6f, \"error_pct\": %s, \"swings\": %d, "
                      "\"amplitude_kept\": %.5f, \"us_per_step\": %.3f}",
                      k ? ", " : "", kRockerNames[r.rocker], contactName(r), r.segments, r.grid, r.dt_ms, r.exact_s,
                      r.period_s, error.c_str(), r.swings, r.kept, r.us_per_step);
    }
    bench::writeTextFile(json, j + "]}\n");
  }
  if (!md.empty()) {
    std::string t = "Measured " + stamp +
                    bench::fmt(". Released 0.05 rad from the bottom of the swing, run %.1f s; the period against the "
                               "rolling equations' (exact); the amplitude kept: the last half swing's over the "
                               "first's; the time per step. Grid: the smooth chart's intervals along the object's "
                               "longer side.\n\n",
                               seconds) +
                    "| object | contact | segments | grid | step | exact | period | error | swings | amplitude kept | cost |\n"
                    "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    for (const Row& r : rows)
      t += bench::fmt("| %s | %s | %d | %s | %g ms | %.4f s | %s | %d | %.3f | %.1f µs |\n", kRockerNames[r.rocker],
                      contactName(r), r.segments, r.smooth ? std::to_string(r.grid).c_str() : "—", r.dt_ms, r.exact_s,
                      periodCell(r).c_str(), std::max(r.swings, 0), r.kept, r.us_per_step);
    bench::writeTextFile(md, t);
  }
  if (!png.empty()) writePlot(png, rows, stamp);
  for (const Row& r : rows)
    std::printf("%s, %s, %d segments, grid %d, %g ms: exact %.4f s, period %.4f s (%+.2f %%), %d swings, kept %.3f, "
                "%.1f us/step\n",
                kRockerNames[r.rocker], contactName(r), r.segments, r.grid, r.dt_ms, r.exact_s, r.period_s,
                r.error_pct, r.swings, r.kept, r.us_per_step);
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return bench::benchMain(argc, argv, kHelp, "bench_rocking_on_curve", run); }
