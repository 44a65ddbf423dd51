// The lifted ball swinging in a textured bowl against a rigid ball's rolling (issue 29; docs/physics.md
// "Textured meshes"): the product's default ball on a relief mesh (MeshContactOptions::lift_ball)
// released 5 degrees up the inside of a UV sphere whose relief is sine bumps, at the pole and on
// the equator, against tests/physics/slope_predicted_swing.hpp's liftedPredictedSwing (the centre
// on the relief as the ball meets it, energy kept while the touch moves, the rolling-impact law
// where it jumps) at two steps; and the lifted ball rolling off the top of that sphere, where it
// leaves against the earliest its bumps' crests allow. Measures only; nothing asserted
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
using thx::phys::test::kPi;

constexpr const char* kHelp = R"(usage: bench_lifted_swing [--slopes S,S,...] [--seconds T] [--departure-slopes S,S,...]
                          [--json F] [--csv F] [--md F]

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

Then the ball released at rest 1 degree off the top of the same sphere (friction 10), where it
leaves (its last step with a normal impulse) against the same scene untextured, simulated at
1 ms and 0.25 ms steps, and with the bumps given as a normal map met as the relief its normals
integrate to (physics-client's ball on a normal-mapped mesh; 1 ms); beside atan(s), and the
earliest a rigid ball can leave over the bumps' crests (where gravity no longer holds it on a
crest's curvature, a k^2) and the latest in their troughs (none where it bridges them or no speed
lifts it out): tests/physics/mesh_rolling_scenes.hpp, earliestDepartureOverCrestsDeg.

  --slopes LIST   steepest slopes of the bumps (default 0.005,0.01,0.02,0.05,0.1)
  --seconds T     the swing's length (default 4)
  --departure-slopes LIST   the roll-off's slopes (default 0.0005,0.002,0.005,0.01,0.02,0.05,0.1)
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

// Where the lifted ball leaves the top, each change against the untextured scene at the same step.
constexpr double kTop = 1.0, kFriction = 10.0, kFineStep = 2.5e-4;
struct DepartureRow {
  double slope = 0;
  double lifted = NAN, lifted_fine = NAN, normal_map = NAN;  // degrees; NAN: it did not leave
  double earliest = 0, latest = NAN;                          // degrees, against departureDeg; NAN: no latest
};

double change(const Swing& with, const Swing& without) {
  return with.periods > 0 && without.periods > 0 ? with.period_s / without.period_s - 1.0 : NAN;
}

int run(int argc, char** argv) {
  std::vector<double> slopes{0.005, 0.01, 0.02, 0.05, 0.1};
  std::vector<double> departure_slopes{0.0005, 0.002, 0.005, 0.01, 0.02, 0.05, 0.1};
  double seconds = 4.0;
  std::string json, csv, md;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (i + 1 >= argc) throw UsageError(a + " needs a value (see --help)");
    const std::string v = argv[++i];
    if (a == "--slopes") slopes = cli::parseNumberList(a, v, {1e-4, 0.5, false, ""});
    else if (a == "--seconds") seconds = cli::parseNumber(a, v, {1.5, 60.0, false, "s"});
    else if (a == "--departure-slopes") departure_slopes = cli::parseNumberList(a, v, {4e-4, 0.5, false, ""});
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
  std::vector<DepartureRow> departures;
  {
    auto moved = [](const Departure& with, const Departure& without) {
      return with.left && without.left ? with.theta_deg - without.theta_deg : NAN;
    };
    const Departure plain = rollOffSphere(kSegments, true, kR, kTop, kFriction);
    const Departure plain_fine = rollOffSphere(kSegments, true, kR, kTop, kFriction, nullptr, nullptr, false, kFineStep);
    for (double slope : departure_slopes) {
      std::fprintf(stderr, "bench_lifted_swing: roll-off, slope %g ...\n", slope);
      const tex::TextureMap map = sineBumps(slope);
      const tex::BallOnRelief relief(map, tex::Address::Wrap);
      const auto implied = normalMapRelief(map, kTileM);
      DepartureRow row;
      row.slope = slope;
      row.lifted = moved(rollOffSphere(kSegments, true, kR, kTop, kFriction, &map, &relief, true), plain);
      row.lifted_fine = moved(rollOffSphere(kSegments, true, kR, kTop, kFriction, &map, &relief, true, kFineStep), plain_fine);
      row.normal_map = moved(rollOffSphere(kSegments, true, kR, kTop, kFriction, &implied->normals, &*implied->ball, true), plain);
      row.earliest = earliestDepartureOverCrestsDeg(kR, kTop, sineBumpsCrestCurvature(slope)) - departureDeg(kTop);
      row.latest = latestDepartureInTroughsDeg(kR, kTop, sineBumpsCrestCurvature(slope)) - departureDeg(kTop);
      departures.push_back(row);
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
    c += "\nslope,atan_s_deg,earliest_over_crests_deg,latest_in_troughs_deg,departure_moved_deg_1ms,departure_moved_deg_250us,normal_map_as_relief_deg_1ms\n";
    for (const DepartureRow& r : departures)
      c += bench::fmt("%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f\n", r.slope, std::atan(r.slope) * 180.0 / kPi, r.earliest, r.latest, r.lifted,
                      r.lifted_fine, r.normal_map);
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
    j += "], \"departures\": [";
    auto number = [](double x) { return std::isfinite(x) ? bench::fmt("%.4f", x) : std::string("null"); };
    for (std::size_t k = 0; k < departures.size(); ++k) {
      const DepartureRow& r = departures[k];
      j += bench::fmt("%s{\"slope\": %.4f, \"atan_s_deg\": %.4f, \"earliest_over_crests_deg\": %.4f, \"latest_in_troughs_deg\": %s, "
                      "\"moved_deg_1ms\": %s, \"moved_deg_250us\": %s, \"normal_map_as_relief_deg_1ms\": %s}",
                      k ? ", " : "", r.slope, std::atan(r.slope) * 180.0 / kPi, r.earliest, number(r.latest).c_str(), number(r.lifted).c_str(),
                      number(r.lifted_fine).c_str(), number(r.normal_map).c_str());
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
    auto angle = [](double x) { return std::isfinite(x) ? bench::fmt("%+.2f°", x) : std::string("stayed on"); };
    t += bench::fmt("\nThe lifted ball released at rest %g° off the top, friction 10: how far its departure (its last step with a "
                    "normal impulse) moved against the same scene untextured at the same step (exact: %.2f°), "
                    "simulated at 1 ms and 0.25 ms steps, and the bumps as a normal map met as the relief its normals "
                    "integrate to (physics-client's ball; 1 ms); beside atan s, and the earliest a rigid ball can leave "
                    "over the bumps' crests (curvature a k², its centre's path 1/l plus the crest's as it rides it) and the latest in "
                    "their troughs (none where the ball bridges them or no speed lifts it out).\n\n",
                    kTop, departureDeg(kTop)) +
         "| slope s | atan s | earliest over crests | latest in troughs | departure moved, 1 ms | 0.25 ms | normal map as its "
         "relief, 1 ms |\n|---:|---:|---:|---:|---:|---:|---:|\n";
    for (const DepartureRow& r : departures)
      t += bench::fmt("| %g | %.2f° | %+.2f° | %s | %s | %s | %s |\n", r.slope, std::atan(r.slope) * 180.0 / kPi, r.earliest,
                      std::isfinite(r.latest) ? bench::fmt("%+.2f°", r.latest).c_str() : "none",
                      angle(r.lifted).c_str(), angle(r.lifted_fine).c_str(), angle(r.normal_map).c_str());
    bench::writeTextFile(md, t);
  }
  for (const Row& r : rows)
    std::printf("%s, s %g: period %+.2f %% (predicted %+.2f / %+.2f %%), swing at the end %.3f (%.3f), kept %.3f, %.0f us/step\n",
                where(r), r.slope, r.simulated * 100, r.predicted * 100, r.predicted_fine * 100, r.amplitude_simulated,
                r.amplitude_predicted, r.speed_kept, r.us_per_step);
  for (const DepartureRow& r : departures)
    std::printf("roll-off, s %g: departure moved %+.2f deg at 1 ms, %+.2f at 0.25 ms, normal map as its relief %+.2f "
                "(atan s %.2f, earliest over crests %+.2f, latest in troughs %+.2f)\n",
                r.slope, r.lifted, r.lifted_fine, r.normal_map, std::atan(r.slope) * 180.0 / kPi, r.earliest, r.latest);
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return bench::benchMain(argc, argv, kHelp, "bench_lifted_swing", run); }
