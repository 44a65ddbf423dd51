// A ball rolling across sine ridges (issue 29; docs/physics.md "A ball on a relief, lifted"):
// the speed it keeps over 60 periods on the relief plane and on a relief mesh (lifted, the
// default, and steered) against the rolling-impact law of a rigid ball rolling without slipping
// (tests/physics/rolling_over_ridges.hpp), with the cost of a step. Measures only; nothing
// asserted (tests/physics/test_relief_mesh_ridges.cpp holds the mesh's behaviour).
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
#include "tests/physics/ridges_scene.hpp"

namespace {

using namespace thx;
using namespace thx::phys::test::ridges;

constexpr const char* kHelp = R"(usage: bench_rolling_ridges [--slopes S,S,...] [--quick] [--json F] [--csv F] [--md F]

A 1 cm, 50 g ball (friction 1) set rolling at 0.25 m/s across sine ridges 2.5 mm apart of
slope s at most (a 256-texel relief over 1 cm, wrapped), on the relief plane and on the same
relief laid on the flat top of a box mesh, the ball lifted onto it (the default) or held on the
smooth surface and steered. The speed it keeps from the 6th period to the 66th (mean speeds over
a period's length), against the rolling-impact law for the ridges as stored (heights linear
between texel centres): energy kept while the touch moves, and v' = v (2 + 5 cos phi) / 7 where
it jumps by phi across a trough the ball cannot reach (troughs sharper than the ball: s above
0.04). At 1 ms and 0.25 ms steps; the time per step is the whole run's (world built, 0.3 s
settling, 1.5 s rolling) over its steps.

  --slopes LIST   ridge slopes (default 0.02,0.05,0.1)
  --quick         1 ms steps only
  --json/--csv/--md F   results
)";

constexpr double kV0 = 0.25, kRollS = 1.5, kSettleS = 0.3;
constexpr Ground kGrounds[] = {Ground::ReliefPlane, Ground::MeshLifted, Ground::MeshSteered};
const char* const kGroundNames[] = {"relief plane", "mesh, lifted", "mesh, steered"};

struct Row {
  double slope = 0, dt = 0, law = 0;
  double kept[3] = {0, 0, 0};
  double us_per_step[3] = {0, 0, 0};
};

int run(int argc, char** argv) {
  std::vector<double> slopes{0.02, 0.05, 0.1}, steps{1e-3, 2.5e-4};
  std::string json, csv, md;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--quick") {
      steps = {1e-3};
      continue;
    }
    if (i + 1 >= argc) throw UsageError(a + " needs a value (see --help)");
    const std::string v = argv[++i];
    if (a == "--slopes") slopes = cli::parseNumberList(a, v, {1e-4, 0.2, false, ""});
    else if (a == "--json") json = v;
    else if (a == "--csv") csv = v;
    else if (a == "--md") md = v;
    else throw UsageError("unknown option " + a + " (see --help)");
  }
  std::vector<Row> rows;
  for (double slope : slopes) {
    const tex::TextureMap map = sineRidges(slope);
    const double law = speedKept(referenceFor(slope).periodMeanSpeeds(kV0, kFirst + kPeriods + 1));
    for (double dt : steps) {
      std::fprintf(stderr, "bench_rolling_ridges: slope %.3g, step %.3g ms ...\n", slope, dt * 1e3);
      Row r;
      r.slope = slope, r.dt = dt, r.law = law;
      for (int g = 0; g < 3; ++g) {
        const auto t0 = std::chrono::steady_clock::now();
        r.kept[g] = speedKept(rollAcross(map, kGrounds[g], dt, kV0, kRollS).period_speeds);
        const auto t1 = std::chrono::steady_clock::now();
        r.us_per_step[g] = std::chrono::duration<double, std::micro>(t1 - t0).count() / ((kSettleS + kRollS) / dt);
      }
      rows.push_back(r);
    }
  }
  const std::string stamp = bench::fmt("%s, %s build, %s", bench::isoNow().c_str(), bench::buildType(),
                                       bench::machineSummary().c_str());
  if (!csv.empty()) {
    std::string c = "slope,step_ms,law,plane,mesh_lifted,mesh_steered,us_plane,us_mesh_lifted,us_mesh_steered\n";
    for (const Row& r : rows)
      c += bench::fmt("%.4f,%.3f,%.5f,%.5f,%.5f,%.5f,%.2f,%.2f,%.2f\n", r.slope, r.dt * 1e3, r.law, r.kept[0], r.kept[1],
                      r.kept[2], r.us_per_step[0], r.us_per_step[1], r.us_per_step[2]);
    bench::writeTextFile(csv, c);
  }
  if (!json.empty()) {
    std::string j = bench::fmt("{\"stamp\": \"%s\", \"periods\": %d, \"rows\": [", stamp.c_str(), kPeriods);
    for (std::size_t k = 0; k < rows.size(); ++k) {
      const Row& r = rows[k];
      j += bench::fmt("%s{\"slope\": %.4f, \"step_ms\": %.3f, \"law\": %.6f, \"plane\": %.6f, \"mesh_lifted\": %.6f, "
                      "\"mesh_steered\": %.6f, \"us_plane\": %.3f, \"us_mesh_lifted\": %.3f, \"us_mesh_steered\": %.3f}",
                      k ? ", " : "", r.slope, r.dt * 1e3, r.law, r.kept[0], r.kept[1], r.kept[2], r.us_per_step[0],
                      r.us_per_step[1], r.us_per_step[2]);
    }
    bench::writeTextFile(json, j + "]}\n");
  }
  if (!md.empty()) {
    std::string t = "Measured " + stamp +
                    bench::fmt(". The speed kept over %d periods (its difference from the rolling-impact law's in "
                               "brackets), and the time per step.\n\n",
                               kPeriods) +
                    "| slope | step | law | relief plane | mesh, lifted | mesh, steered | step: plane | lifted | steered |\n"
                    "|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    for (const Row& r : rows) {
      t += bench::fmt("| %.2f | %.2f ms | %.4f |", r.slope, r.dt * 1e3, r.law);
      for (int g = 0; g < 3; ++g) t += bench::fmt(" %.4f (%+.3f) |", r.kept[g], r.kept[g] - r.law);
      t += bench::fmt(" %.0f µs | %.0f µs | %.0f µs |\n", r.us_per_step[0], r.us_per_step[1], r.us_per_step[2]);
    }
    bench::writeTextFile(md, t);
  }
  for (const Row& r : rows) {
    std::printf("slope %.3f, step %.2f ms: law %.4f", r.slope, r.dt * 1e3, r.law);
    for (int g = 0; g < 3; ++g) std::printf("; %s %.4f (%.0f us/step)", kGroundNames[g], r.kept[g], r.us_per_step[g]);
    std::printf("\n");
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return bench::benchMain(argc, argv, kHelp, "bench_rolling_ridges", run); }
