// The lifted ball swinging in a textured bowl against a rigid ball's rolling (issue 29; docs/physics.md
// "Textured meshes"): the product's default ball on a relief mesh (MeshContactOptions::lift_ball)
// released 5 degrees up the inside of a UV sphere whose relief is sine bumps, at the pole and on
// the equator, against tests/physics/slope_predicted_swing.hpp's liftedPredictedSwing (the centre
// on the relief as the ball meets it, energy kept while the touch moves, the rolling-impact law
// where it jumps) at two steps. Measures only; nothing asserted
// (tests/physics/test_mesh_rolling.cpp holds the behaviour).
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
#include "tests/physics/slope_predicted_swing.hpp"

namespace {

using namespace thx;
using namespace thx::phys::test::mesh_rolling;

constexpr const char* kHelp = R"(usage: bench_lifted_swing [--slopes S,S,...] [--seconds T] [--json F] [--csv F] [--md F]

A 1 cm, 50 g ball released at rest 5 degrees up the inside of a UV sphere of radius 10 cm (128
segments) whose relief is sine bumps 2.5 mm apart of steepest slope S (one tile of 256 texels per
cm of arc), met as the product meets it by default: lifted onto the relief as its sphere meets it.
The bottom at the UV sphere's pole (where the uv squeezes the bumps along u) or on its equator
(the texture at its stated scale). Simulated at 1 ms steps for T seconds; predicted for the same
release by a rigid ball rolling without slipping on that lifted relief, its energy kept where its
touch moves continuously and the rolling-impact law v' = v (2 + 5 cos phi) / 7 where it jumps,
integrated at 0.1 ms and at 25 us. Each period is compared with the same scene untextured
(simulated, and the prediction's own). Also the largest distance from the bottom along the swing
in the last second, over the release's, and the speed the prediction's jumps kept in all.

  --slopes LIST   steepest slopes of the bumps (default 0.005,0.01,0.02,0.05,0.1)
  --seconds T     the swing's length (default 4)
  --json/--csv/--md F   results
)";

constexpr double kR = 0.1, kRelease = 5.0;
constexpr int kSegments = 128;
constexpr double kPredictionSteps[] = {1e-4, 2.5e-5};

struct Row {
  double slope = 0;
  bool equator = false;
  double simulated = 0, predicted = 0, predicted_fine = 0;  // the period's change
  int periods = 0;
  double amplitude_simulated = 0, amplitude_predicted = 0;  // over the release's
  double speed_kept = 0;                                    // the fine prediction's jumps, in all
  double us_per_step = 0;
};

double change(const Swing& with, const Swing& without) {
  return with.periods > 0 && without.periods > 0 ? with.period_s / without.period_s - 1.0 : NAN;
}

int run(int argc, char** argv) {
  std::vector<double> slopes{0.005, 0.01, 0.02, 0.05, 0.1};
  double seconds = 4.0;
  std::string json, csv, md;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (i + 1 >= argc) throw UsageError(a + " needs a value (see --help)");
    const std::string v = argv[++i];
    if (a == "--slopes") slopes = cli::parseNumberList(a, v, {1e-4, 0.5, false, ""});
    else if (a == "--seconds") seconds = cli::parseNumber(a, v, {1.5, 60.0, false, "s"});
    else if (a == "--json") json = v;
    else if (a == "--csv") csv = v;
    else if (a == "--md") md = v;
    else throw UsageError("unknown option " + a + " (see --help)");
  }
  const double release_m = (kR - kBallRadius) * std::sin(phys::test::deg(kRelease));
  std::vector<Row> rows;
  for (bool equator : {false, true}) {
    const Eigen::Matrix3d turn = equator ? bottomOnTheEquator(kR) : Eigen::Matrix3d::Identity();
    const Swing plain = swingInBowl(kSegments, true, kR, kRelease, seconds, nullptr, turn);
    Swing plain_predicted[2];
    for (int k = 0; k < 2; ++k)
      plain_predicted[k] = slopePredictedSwing(kSegments, kR, kRelease, seconds, nullptr, turn, nullptr, kPredictionSteps[k]);
    for (double slope : slopes) {
      std::fprintf(stderr, "bench_lifted_swing: %s, slope %g ...\n", equator ? "equator" : "pole", slope);
      const tex::TextureMap map = sineBumps(slope);
      const tex::BallOnRelief relief(map, tex::Address::Wrap);
      Row row;
      row.slope = slope, row.equator = equator;
      const Swing simulated = swingInBowl(kSegments, true, kR, kRelease, seconds, &map, turn, &relief, kDt, true);
      const Swing predicted = liftedPredictedSwing(kSegments, kR, kRelease, seconds, map, relief, turn, kPredictionSteps[0]);
      const Swing fine = liftedPredictedSwing(kSegments, kR, kRelease, seconds, map, relief, turn, kPredictionSteps[1], &row.speed_kept);
      row.simulated = change(simulated, plain);
      row.predicted = change(predicted, plain_predicted[0]);
      row.predicted_fine = change(fine, plain_predicted[1]);
      row.periods = simulated.periods;
      row.amplitude_simulated = simulated.end_amplitude_m / release_m;
      row.amplitude_predicted = fine.end_amplitude_m / release_m;
      row.us_per_step = simulated.us_per_step;
      rows.push_back(row);
    }
  }
  const std::string stamp = bench::fmt("%s, %s build, %s", bench::isoNow().c_str(), bench::buildType(),
                                       bench::machineSummary().c_str());
  auto where = [](const Row& r) { return r.equator ? "equator" : "pole"; };
  if (!csv.empty()) {
    std::string c = "bottom,slope,simulated,predicted_100us,predicted_25us,periods,amplitude_simulated,amplitude_predicted,speed_kept,us_per_step\n";
    for (const Row& r : rows)
      c += bench::fmt("%s,%.4f,%.5f,%.5f,%.5f,%d,%.4f,%.4f,%.4f,%.2f\n", where(r), r.slope, r.simulated, r.predicted,
                      r.predicted_fine, r.periods, r.amplitude_simulated, r.amplitude_predicted, r.speed_kept, r.us_per_step);
    bench::writeTextFile(csv, c);
  }
  if (!json.empty()) {
    std::string j = bench::fmt("{\"stamp\": \"%s\", \"seconds\": %.2f, \"rows\": [", stamp.c_str(), seconds);
    for (std::size_t k = 0; k < rows.size(); ++k) {
      const Row& r = rows[k];
      j += bench::fmt("%s{\"bottom\": \"%s\", \"slope\": %.4f, \"simulated\": %.6f, \"predicted_100us\": %.6f, "
                      "\"predicted_25us\": %.6f, \"periods\": %d, \"amplitude_simulated\": %.5f, "
                      "\"amplitude_predicted\": %.5f, \"speed_kept\": %.5f, \"us_per_step\": %.3f}",
                      k ? ", " : "", where(r), r.slope, r.simulated, r.predicted, r.predicted_fine, r.periods,
                      r.amplitude_simulated, r.amplitude_predicted, r.speed_kept, r.us_per_step);
    }
    bench::writeTextFile(json, j + "]}\n");
  }
  if (!md.empty()) {
    std::string t = "Measured " + stamp +
                    bench::fmt(". The lifted ball (the default) released 5° up a 10 cm UV sphere of 128 segments, %.0f s at "
                               "1 ms steps; its period's change against the same scene untextured, simulated and "
                               "predicted (a rigid ball rolling on the relief as its sphere meets it, the rolling-impact "
                               "law where its touch jumps) at 0.1 ms and 25 µs steps; the swing's largest distance from "
                               "the bottom in the last second over the release's, simulated and predicted (25 µs); the "
                               "speed the prediction's jumps kept in all; the time per simulated step.\n\n",
                               seconds) +
                    "| bottom | slope s | period changed | predicted, 0.1 ms | 25 µs | periods | swing at the end | "
                    "predicted | speed kept at jumps | step |\n|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    for (const Row& r : rows)
      t += bench::fmt("| %s | %g | %+.2f %% | %+.2f %% | %+.2f %% | %d | %.3f | %.3f | %.3f | %.0f µs |\n", where(r), r.slope,
                      r.simulated * 100, r.predicted * 100, r.predicted_fine * 100, r.periods, r.amplitude_simulated,
                      r.amplitude_predicted, r.speed_kept, r.us_per_step);
    bench::writeTextFile(md, t);
  }
  for (const Row& r : rows)
    std::printf("%s, s %g: period %+.2f %% (predicted %+.2f / %+.2f %%), swing at the end %.3f (%.3f), kept %.3f, %.0f us/step\n",
                where(r), r.slope, r.simulated * 100, r.predicted * 100, r.predicted_fine * 100, r.amplitude_simulated,
                r.amplitude_predicted, r.speed_kept, r.us_per_step);
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return bench::benchMain(argc, argv, kHelp, "bench_lifted_swing", run); }
