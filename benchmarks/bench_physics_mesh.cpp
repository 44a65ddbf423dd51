// Speed against error of Bullet bodies on tessellated curved meshes (issue 29; docs/physics.md
// "Textured meshes"): a ball swinging inside a UV sphere of radius 10 cm (the bowl) and a ball
// rolling off its top, against the smooth sphere's analytic answers (the rolling period
// 2 pi sqrt(7 (R - r) / 5 g); departure at cos(theta) = 10/17 cos(theta_0)), by tessellation,
// with the contacts steered by the smooth surface (clients/physics/mesh_contact.hpp) and with
// Bullet's own contacts on the flat triangles (the baseline); and the cost of a step. Measures
// only; nothing asserted (tests/physics/test_mesh_rolling.cpp holds the analytic answers).
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <stdexcept>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

#include "base/cli_number.hpp"
#include "base/error.hpp"
#include "benchmarks/bench_help.hpp"
#include "benchmarks/bench_rig.hpp"
#include "benchmarks/bench_stamp.hpp"
#include "clients/study/stats.hpp"
#include "tests/physics/mesh_rolling_scenes.hpp"
#include "tests/physics/slope_predicted_swing.hpp"
#include "tools/report/plot.hpp"

namespace {

using namespace thx;
using namespace thx::phys::test::mesh_rolling;
using thx::phys::test::kPi;

constexpr const char* kHelp = R"(usage: bench_physics_mesh [--segments N,N,...] [--seconds S] [--texture-segments N] [--quick]
                          [--json F] [--csv F] [--md F] [--png F]

A 1 cm, 50 g ball on UV spheres of radius 10 cm tessellated with N segments around and N/2
rings (meshes/mesh_generators.hpp), at 1 ms steps:
  bowl:     released 5 degrees up the inside; its swing period against the rolling period
            2 pi sqrt(7 (R - r) / (5 g)) = 0.71208 s, over the run's whole periods;
  roll-off: released at rest 1 degree off the top, friction 10; where it leaves (its last step
            with a normal impulse) against cos(theta) = 10/17 cos(1 deg): 53.97 degrees.
Each with the contacts steered by the smooth surface (the default of
PhysicsWorld::addTexturedMesh) and with Bullet's own contacts on the flat triangles; and the
wall-clock time of a step in the bowl (one ball, the mesh static). Then both scenes on one
tessellation with a fine texture: sine bumps 2.5 mm apart (tests/physics/mesh_rolling_scenes.hpp)
whose steepest slope s is 0.005 to 0.1, against the same scene untextured; the departure's change
beside atan(s), the most the texture can tilt the surface; the bowl's period change beside the
change the texture's slopes predict (tests/physics/slope_predicted_swing.hpp: the same slopes
read at the foot, the ball's rolling integrated without Bullet at 0.1 ms), with the bowl's
bottom at the sphere's pole (where the uv squeezes the texture) and turned onto its equator
(where the texture lies at its stated scale); the same with the bumps as a relief met as the
ball's sphere meets it (textures/ball_on_relief.hpp), and the cost of a step each way; and on the
equator, released at 4.90 to 5.10 degrees, where which bump the ball turns at decides the period;
and there the relief again with the simulation at 1, 0.5, 0.25 and 0.1 ms steps and the
prediction at 0.025 ms (whether the simulation and the prediction have settled in their steps);
and at s = 0.1, many releases from 4.80 to 5.20 degrees read each way, simulated at 1 and 0.25
ms and predicted at 0.1 and 0.025 ms: the mean change over the releases, and each row's mean
difference from the 0.1 ms prediction, release by release, with its standard error and how far
neighbouring releases' differences are correlated.

  --segments LIST   tessellations (default 16,24,32,48,64,96,128,192,256)
  --seconds S       simulated time of each bowl run (default 4)
  --texture-segments N  the tessellation of the textured runs (default 128)
  --releases N      releases in the last table (default 100)
  --threads N       threads for the last table's releases (default: the machine's cores); the
                    wall-clock columns are all measured before it, on one thread
  --quick           a short run (3 tessellations, 2 s, 10 releases)
  --json/--csv/--md/--png F   results
)";

struct BowlChange {
  double simulated = 0, predicted = 0;  // relative to the untextured run of each
  int periods = 0;                      // whole periods simulated
  double us_per_step = 0;               // the simulation's, wall clock
};

struct TexturedRow {
  double slope = 0;
  BowlChange pole, equator;                // the texture read at one point
  BowlChange pole_relief, equator_relief;  // as the ball's sphere meets the relief
  double leave_change_deg = 0;
  bool left = false;
};

constexpr double kReleasesDeg[] = {4.9, 4.95, 5.0, 5.05, 5.1};

// How many of the releases' changes a and b agree within `points`.
int agreeing(const std::vector<double>& a, const std::vector<double>& b, double points) {
  int n = 0;
  for (std::size_t k = 0; k < a.size() && k < b.size(); ++k) n += std::fabs(a[k] - b[k]) <= points;
  return n;
}

struct ReleaseRow {
  double slope = 0;
  bool ball_on_relief = false;
  std::vector<double> simulated, predicted;  // the period's change at each of kReleasesDeg (the bottom on the equator)
  int within(double points) const { return agreeing(simulated, predicted, points); }
  static double mean(const std::vector<double>& v) { return study::summarize(v).mean; }
};

// The relief on the equator at each release, simulated at one step (or predicted at one, `predicted`).
constexpr double kSimulatedStepsS[] = {1e-3, 5e-4, 2.5e-4, 1e-4};
constexpr double kFinePredictionStepS = 2.5e-5;
struct StepRow {
  double slope = 0;
  bool predicted = false;
  double step_s = 0;
  std::vector<double> change;       // at each of kReleasesDeg
  double wall_per_simulated = NAN;  // simulated rows: wall-clock seconds per simulated second
};

// At s = 0.1 which crest the ball turns at is not settled in either integration's step, so the
// period at one release is not a number to compare; their means over many releases are.
constexpr double kManySlope = 0.1;
double manyRelease(int i, int count) { return 4.8 + 0.4 * (i + 0.5) / count; }  // evenly over 4.80 to 5.20 degrees
double sampleDeviation(const std::vector<double>& v) { return study::summarize(v).sd; }
// The standard error of v's mean, were its entries independent; neighbourCorrelation says how far
// they are (the releases are evenly spaced, and a period's change can run smoothly from one to the next).
double standardError(const std::vector<double>& v) { return sampleDeviation(v) / std::sqrt(double(v.size())); }
// The correlation of each entry with the next (lag 1).
double neighbourCorrelation(const std::vector<double>& v) {
  const double mean = ReleaseRow::mean(v);
  double products = 0, squares = 0;
  for (std::size_t k = 0; k < v.size(); ++k) {
    squares += (v[k] - mean) * (v[k] - mean);
    if (k + 1 < v.size()) products += (v[k] - mean) * (v[k + 1] - mean);
  }
  return squares > 0 ? products / squares : NAN;
}
struct ManyRow {
  bool ball_on_relief = false, predicted = false;
  double step_s = 0;
  std::vector<double> change;  // at each of the releases
  double mean() const { return ReleaseRow::mean(change); }
  double deviation() const { return sampleDeviation(change); }
  // Release by release, this row's change less `reference`'s (the same releases).
  std::vector<double> differenceFrom(const ManyRow& reference) const {
    std::vector<double> d;
    for (std::size_t k = 0; k < change.size() && k < reference.change.size(); ++k) d.push_back(change[k] - reference.change[k]);
    return d;
  }
};

struct Row {
  int segments = 0;
  std::size_t triangles = 0;
  double period_smooth = 0, period_flat = 0;  // relative error
  double leave_smooth = 0, leave_flat = 0;    // degrees, signed
  bool left_smooth = false, left_flat = false;
  double us_smooth = 0, us_flat = 0;
};


int run(int argc, char** argv) {
  std::vector<int> segments{16, 24, 32, 48, 64, 96, 128, 192, 256};
  double seconds = 4.0;
  int texture_segments = 128;
  int many_releases = 100;
  int threads = int(std::max(1u, std::thread::hardware_concurrency()));
  std::string json, csv, md, png;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--quick") {
      segments = {32, 64, 128};
      seconds = 2.0;
      many_releases = 10;
      continue;
    }
    if (i + 1 >= argc) throw UsageError(a + " needs a value (see --help)");
    const std::string v = argv[++i];
    if (a == "--segments") segments = cli::parseIntegerList(a, v, 6, 2048);
    else if (a == "--seconds") seconds = cli::parseNumber(a, v, {0.5, 600.0, false, "s"});
    else if (a == "--texture-segments") texture_segments = int(cli::parseInteger(a, v, 6, 2048));
    else if (a == "--releases") many_releases = int(cli::parseInteger(a, v, 2, 10000));
    else if (a == "--threads") threads = int(cli::parseInteger(a, v, 1, 256));
    else if (a == "--json") json = v;
    else if (a == "--csv") csv = v;
    else if (a == "--md") md = v;
    else if (a == "--png") png = v;
    else throw UsageError("unknown option " + a + " (see --help)");
  }

  constexpr double kR = 0.1, kTheta0 = 1.0, kSwing0 = 5.0, kFriction = 10.0;
  const double period = swingPeriod(kR), leave = departureDeg(kTheta0);
  std::vector<Row> rows;
  std::fprintf(stderr, "bench_physics_mesh:");
  for (int n : segments) {
    std::fprintf(stderr, " %d", n);
    Row r;
    r.segments = n;
    r.triangles = mesh::sphere(kR, n, n / 2, 0.01).mesh.triangles.size();
    const Swing smooth = swingInBowl(n, true, kR, kSwing0, seconds), flat = swingInBowl(n, false, kR, kSwing0, seconds);
    r.period_smooth = smooth.periods > 0 ? smooth.period_s / period - 1.0 : NAN;
    r.period_flat = flat.periods > 0 ? flat.period_s / period - 1.0 : NAN;
    r.us_smooth = smooth.us_per_step, r.us_flat = flat.us_per_step;
    const Departure ds = rollOffSphere(n, true, kR, kTheta0, kFriction), df = rollOffSphere(n, false, kR, kTheta0, kFriction);
    r.left_smooth = ds.left, r.left_flat = df.left;
    r.leave_smooth = ds.theta_deg - leave, r.leave_flat = df.theta_deg - leave;
    rows.push_back(r);
  }
  std::fprintf(stderr, ", textured:");
  std::vector<TexturedRow> textured;
  const Eigen::Matrix3d pole = Eigen::Matrix3d::Identity(), equator = bottomOnTheEquator(kR);
  auto change = [](const Swing& with, const Swing& without) {
    return with.periods > 0 && without.periods > 0 ? with.period_s / without.period_s - 1.0 : NAN;
  };
  struct Untextured {
    Eigen::Matrix3d turn;
    Swing simulated, predicted;
  };
  auto untextured = [&](const Eigen::Matrix3d& turn) {
    return Untextured{turn, swingInBowl(texture_segments, true, kR, kSwing0, seconds, nullptr, turn),
                      slopePredictedSwing(texture_segments, kR, kSwing0, seconds, nullptr, turn)};
  };
  const Untextured at_pole = untextured(pole), on_equator = untextured(equator);
  auto bowlChange = [&](const tex::TextureMap& map, const Untextured& plain, const tex::BallOnRelief* relief) {
    const Swing simulated = swingInBowl(texture_segments, true, kR, kSwing0, seconds, &map, plain.turn, relief);
    BowlChange b;
    b.simulated = change(simulated, plain.simulated);
    b.predicted = change(slopePredictedSwing(texture_segments, kR, kSwing0, seconds, &map, plain.turn, relief), plain.predicted);
    b.periods = simulated.periods;
    b.us_per_step = simulated.us_per_step;
    return b;
  };
  const Departure plain_leave = rollOffSphere(texture_segments, true, kR, kTheta0, kFriction);
  for (double slope : {0.005, 0.01, 0.02, 0.05, 0.1}) {
    std::fprintf(stderr, " %g", slope);
    const tex::TextureMap map = sineBumps(slope);
    const Departure d = rollOffSphere(texture_segments, true, kR, kTheta0, kFriction, &map);
    TexturedRow t;
    t.slope = slope;
    const tex::BallOnRelief relief(map, tex::Address::Wrap);
    t.pole = bowlChange(map, at_pole, nullptr);
    t.equator = bowlChange(map, on_equator, nullptr);
    t.pole_relief = bowlChange(map, at_pole, &relief);
    t.equator_relief = bowlChange(map, on_equator, &relief);
    t.left = d.left && plain_leave.left;
    t.leave_change_deg = d.theta_deg - plain_leave.theta_deg;
    textured.push_back(t);
  }
  // Where the bumps are as steep as the swing (its own slope at the ends is 0.087), which bump the
  // ball turns at decides the period: the same comparison released a little higher or lower.
  std::fprintf(stderr, ", releases:");
  std::vector<Untextured> plain_at_release;
  for (double deg : kReleasesDeg)
    plain_at_release.push_back({equator, swingInBowl(texture_segments, true, kR, deg, seconds, nullptr, equator),
                                slopePredictedSwing(texture_segments, kR, deg, seconds, nullptr, equator)});
  std::vector<ReleaseRow> releases;
  for (double slope : {0.02, 0.05, 0.1}) {
    std::fprintf(stderr, " %g", slope);
    const tex::TextureMap map = sineBumps(slope);
    const tex::BallOnRelief relief(map, tex::Address::Wrap);
    for (const tex::BallOnRelief* read : {(const tex::BallOnRelief*)nullptr, &relief}) {
      ReleaseRow row;
      row.slope = slope, row.ball_on_relief = read != nullptr;
      for (std::size_t k = 0; k < std::size(kReleasesDeg); ++k) {
        const double deg = kReleasesDeg[k];
        const Swing simulated = swingInBowl(texture_segments, true, kR, deg, seconds, &map, equator, read);
        const Swing predicted = slopePredictedSwing(texture_segments, kR, deg, seconds, &map, equator, read);
        row.simulated.push_back(change(simulated, plain_at_release[k].simulated));
        row.predicted.push_back(change(predicted, plain_at_release[k].predicted));
      }
      releases.push_back(row);
    }
  }
  // The relief's rows again by step: the simulation at finer steps, and the prediction at a finer
  // step than its own 0.1 ms (whether the reference itself has settled).
  std::fprintf(stderr, ", steps:");
  std::vector<StepRow> steps;
  std::vector<std::vector<Swing>> plain_at_step(std::size(kSimulatedStepsS));
  for (std::size_t i = 0; i < std::size(kSimulatedStepsS); ++i)
    for (double deg : kReleasesDeg)
      plain_at_step[i].push_back(swingInBowl(texture_segments, true, kR, deg, seconds, nullptr, equator, nullptr, kSimulatedStepsS[i]));
  std::vector<Swing> plain_fine_prediction;
  for (double deg : kReleasesDeg)
    plain_fine_prediction.push_back(slopePredictedSwing(texture_segments, kR, deg, seconds, nullptr, equator, nullptr, kFinePredictionStepS));
  for (double slope : {0.05, 0.1}) {
    std::fprintf(stderr, " %g", slope);
    const tex::TextureMap map = sineBumps(slope);
    const tex::BallOnRelief relief(map, tex::Address::Wrap);
    StepRow fine;
    fine.slope = slope, fine.predicted = true, fine.step_s = kFinePredictionStepS;
    for (std::size_t k = 0; k < std::size(kReleasesDeg); ++k)
      fine.change.push_back(change(slopePredictedSwing(texture_segments, kR, kReleasesDeg[k], seconds, &map, equator, &relief,
                                                       kFinePredictionStepS),
                                   plain_fine_prediction[k]));
    steps.push_back(fine);
    for (std::size_t i = 0; i < std::size(kSimulatedStepsS); ++i) {
      StepRow row;
      row.slope = slope, row.step_s = kSimulatedStepsS[i];
      double us = 0;
      for (std::size_t k = 0; k < std::size(kReleasesDeg); ++k) {
        const Swing simulated = swingInBowl(texture_segments, true, kR, kReleasesDeg[k], seconds, &map, equator, &relief, row.step_s);
        row.change.push_back(change(simulated, plain_at_step[i][k]));
        us += simulated.us_per_step;
      }
      row.wall_per_simulated = us / double(std::size(kReleasesDeg)) * 1e-6 / row.step_s;
      steps.push_back(row);
    }
  }
  // The 0.1 ms prediction of each slope's relief rows (the release table's).
  auto reference = [&](double slope) -> const std::vector<double>& {
    for (const ReleaseRow& r : releases)
      if (r.ball_on_relief && r.slope == slope) return r.predicted;
    throw std::logic_error("no release row for the slope");
  };
  // Many releases at s = 0.1: each read simulated at 1 and 0.25 ms and predicted at 0.1 and
  // 0.025 ms, against the untextured swing at the same step. The releases are independent (each
  // swing builds its own world), so they are shared out over threads; nothing here is timed.
  std::fprintf(stderr, ", %d releases on %d threads:", many_releases, threads);
  constexpr double kManySimulatedS[] = {1e-3, 2.5e-4}, kManyPredictedS[] = {1e-4, kFinePredictionStepS};
  std::vector<ManyRow> many;
  {
    const tex::TextureMap map = sineBumps(kManySlope);
    const tex::BallOnRelief relief(map, tex::Address::Wrap);
    for (const tex::BallOnRelief* read : {(const tex::BallOnRelief*)nullptr, &relief}) {
      for (double step : kManySimulatedS) many.push_back({read != nullptr, false, step, std::vector<double>(std::size_t(many_releases))});
      for (double step : kManyPredictedS) many.push_back({read != nullptr, true, step, std::vector<double>(std::size_t(many_releases))});
    }
    std::atomic<int> next{0}, done{0};
    auto work = [&] {
      for (int i; (i = next++) < many_releases;) {
        const double deg = manyRelease(i, many_releases);
        // The untextured swings, one per step (both reads share them).
        Swing plain_simulated[std::size(kManySimulatedS)], plain_predicted[std::size(kManyPredictedS)];
        for (std::size_t k = 0; k < std::size(kManySimulatedS); ++k)
          plain_simulated[k] = swingInBowl(texture_segments, true, kR, deg, seconds, nullptr, equator, nullptr, kManySimulatedS[k]);
        for (std::size_t k = 0; k < std::size(kManyPredictedS); ++k)
          plain_predicted[k] = slopePredictedSwing(texture_segments, kR, deg, seconds, nullptr, equator, nullptr, kManyPredictedS[k]);
        for (ManyRow& row : many) {  // each thread writes only its own release's cells
          const tex::BallOnRelief* read = row.ball_on_relief ? &relief : nullptr;
          const std::size_t k = row.step_s == (row.predicted ? kManyPredictedS[0] : kManySimulatedS[0]) ? 0 : 1;
          row.change[std::size_t(i)] =
              row.predicted
                  ? change(slopePredictedSwing(texture_segments, kR, deg, seconds, &map, equator, read, row.step_s), plain_predicted[k])
                  : change(swingInBowl(texture_segments, true, kR, deg, seconds, &map, equator, read, row.step_s), plain_simulated[k]);
        }
        std::fprintf(stderr, " %d", ++done);
      }
    };
    std::vector<std::thread> workers;
    for (int t = 1; t < threads; ++t) workers.emplace_back(work);
    work();
    for (std::thread& w : workers) w.join();
  }
  // The 0.1 ms prediction of the same read.
  auto manyReference = [&](bool ball_on_relief) -> const ManyRow& {
    for (const ManyRow& r : many)
      if (r.predicted && r.ball_on_relief == ball_on_relief && r.step_s == kManyPredictedS[0]) return r;
    throw std::logic_error("no 0.1 ms prediction");
  };
  std::fprintf(stderr, "\n");

  const std::string stamp = bench::fmt("%s, %s build, %s", bench::isoNow().c_str(), bench::buildType(),
                                       bench::machineSummary().c_str());
  if (!csv.empty()) {
    std::string c = "segments,triangles,period_error_smooth,period_error_flat,departure_error_deg_smooth,"
                    "departure_error_deg_flat,us_per_step_smooth,us_per_step_flat\n";
    for (const Row& r : rows)
      c += bench::fmt("%d,%zu,%.6g,%.6g,%.4f,%.4f,%.2f,%.2f\n", r.segments, r.triangles, r.period_smooth, r.period_flat,
                      r.leave_smooth, r.leave_flat, r.us_smooth, r.us_flat);
    c += "\ntextured_segments,slope,read,bottom,period_change,period_change_predicted,periods,us_per_step\n";
    for (const TexturedRow& t : textured)
      for (const auto& [read, bottom, b] : {std::tuple{"one point", "pole", t.pole}, std::tuple{"one point", "equator", t.equator},
                                            std::tuple{"ball on relief", "pole", t.pole_relief},
                                            std::tuple{"ball on relief", "equator", t.equator_relief}})
        c += bench::fmt("%d,%g,%s,%s,%.6g,%.6g,%d,%.2f\n", texture_segments, t.slope, read, bottom, b.simulated, b.predicted, b.periods,
                        b.us_per_step);
    c += "\ntextured_segments,slope,read,release_deg,period_change,period_change_predicted\n";
    for (const ReleaseRow& r : releases)
      for (std::size_t k = 0; k < r.simulated.size(); ++k)
        c += bench::fmt("%d,%g,%s,%g,%.6g,%.6g\n", texture_segments, r.slope, r.ball_on_relief ? "ball on relief" : "one point",
                        kReleasesDeg[k], r.simulated[k], r.predicted[k]);
    c += "\ntextured_segments,slope,read,step_s,release_deg,period_change,wall_s_per_simulated_s\n";
    for (const StepRow& r : steps)
      for (std::size_t k = 0; k < r.change.size(); ++k)
        c += bench::fmt("%d,%g,%s,%g,%g,%.6g,%.4g\n", texture_segments, r.slope, r.predicted ? "predicted" : "simulated", r.step_s,
                        kReleasesDeg[k], r.change[k], r.wall_per_simulated);
    c += "\ntextured_segments,slope,read,what,step_s,release_deg,period_change\n";
    for (const ManyRow& r : many)
      for (std::size_t k = 0; k < r.change.size(); ++k)
        c += bench::fmt("%d,%g,%s,%s,%g,%.4f,%.6g\n", texture_segments, kManySlope, r.ball_on_relief ? "ball on relief" : "one point",
                        r.predicted ? "predicted" : "simulated", r.step_s, manyRelease(int(k), many_releases), r.change[k]);
    c += "\ntextured_segments,slope,departure_change_deg,slope_angle_deg\n";
    for (const TexturedRow& t : textured)
      c += bench::fmt("%d,%g,%.4f,%.4f\n", texture_segments, t.slope, t.leave_change_deg, std::atan(t.slope) * 180.0 / kPi);
    bench::writeTextFile(csv, c);
  }
  if (!json.empty()) {
    std::string j = "{\n  \"benchmark\": \"balls on tessellated spheres against the smooth sphere's answers\",\n";
    j += bench::fmt("  \"measured\": \"%s\",\n  \"exact_period_s\": %.6f,\n  \"exact_departure_deg\": %.4f,\n  \"rows\": [\n",
                    stamp.c_str(), period, leave);
    for (std::size_t i = 0; i < rows.size(); ++i) {
      const Row& r = rows[i];
      j += bench::fmt("    {\"segments\": %d, \"triangles\": %zu, \"period_error_smooth\": %.6g, \"period_error_flat\": %.6g, "
                      "\"departure_error_deg_smooth\": %.4f, \"departure_error_deg_flat\": %.4f, \"left_smooth\": %s, "
                      "\"left_flat\": %s, \"us_per_step_smooth\": %.2f, \"us_per_step_flat\": %.2f}%s\n",
                      r.segments, r.triangles, r.period_smooth, r.period_flat, r.leave_smooth, r.leave_flat,
                      r.left_smooth ? "true" : "false", r.left_flat ? "true" : "false", r.us_smooth, r.us_flat,
                      i + 1 < rows.size() ? "," : "");
    }
    j += bench::fmt("  ],\n  \"textured_segments\": %d,\n  \"textured\": [\n", texture_segments);
    for (std::size_t i = 0; i < textured.size(); ++i) {
      const TexturedRow& t = textured[i];
      auto bowl = [](const BowlChange& b) {
        return bench::fmt("{\"period_change\": %.6g, \"period_change_predicted\": %.6g, \"periods\": %d, \"us_per_step\": %.2f}",
                          b.simulated, b.predicted, b.periods, b.us_per_step);
      };
      j += bench::fmt("    {\"slope\": %g, \"bowl_at_pole\": %s, \"bowl_on_equator\": %s, \"bowl_at_pole_ball_on_relief\": %s, "
                      "\"bowl_on_equator_ball_on_relief\": %s, \"departure_change_deg\": %.4f, \"left\": %s, "
                      "\"slope_angle_deg\": %.4f}%s\n",
                      t.slope, bowl(t.pole).c_str(), bowl(t.equator).c_str(), bowl(t.pole_relief).c_str(),
                      bowl(t.equator_relief).c_str(), t.leave_change_deg, t.left ? "true" : "false",
                      std::atan(t.slope) * 180.0 / kPi, i + 1 < textured.size() ? "," : "");
    }
    j += "  ],\n  \"releases_on_equator\": [\n";
    for (std::size_t i = 0; i < releases.size(); ++i) {
      const ReleaseRow& r = releases[i];
      std::string cells;
      for (std::size_t k = 0; k < r.simulated.size(); ++k)
        cells += bench::fmt("%s{\"release_deg\": %g, \"period_change\": %.6g, \"period_change_predicted\": %.6g}", k ? ", " : "",
                            kReleasesDeg[k], r.simulated[k], r.predicted[k]);
      j += bench::fmt("    {\"slope\": %g, \"read\": \"%s\", \"releases\": [%s]}%s\n", r.slope,
                      r.ball_on_relief ? "ball on relief" : "one point", cells.c_str(), i + 1 < releases.size() ? "," : "");
    }
    j += "  ],\n  \"relief_on_equator_by_step\": [\n";
    for (std::size_t i = 0; i < steps.size(); ++i) {
      const StepRow& r = steps[i];
      std::string cells;
      for (std::size_t k = 0; k < r.change.size(); ++k)
        cells += bench::fmt("%s{\"release_deg\": %g, \"period_change\": %.6g}", k ? ", " : "", kReleasesDeg[k], r.change[k]);
      j += bench::fmt("    {\"slope\": %g, \"read\": \"%s\", \"step_s\": %g, \"wall_s_per_simulated_s\": %s, \"releases\": [%s]}%s\n",
                      r.slope, r.predicted ? "predicted" : "simulated", r.step_s,
                      std::isfinite(r.wall_per_simulated) ? bench::fmt("%.4g", r.wall_per_simulated).c_str() : "null", cells.c_str(),
                      i + 1 < steps.size() ? "," : "");
    }
    j += bench::fmt("  ],\n  \"many_releases\": {\"slope\": %g, \"releases_deg\": [%g, %g], \"count\": %d, \"rows\": [\n", kManySlope,
                    manyRelease(0, many_releases), manyRelease(many_releases - 1, many_releases), many_releases);
    auto correlation = [](const std::vector<double>& v) {  // null where it is undefined (no spread)
      const double c = neighbourCorrelation(v);
      return std::isfinite(c) ? bench::fmt("%.4f", c) : std::string("null");
    };
    for (std::size_t i = 0; i < many.size(); ++i) {
      const ManyRow& r = many[i];
      const std::vector<double> d = r.differenceFrom(manyReference(r.ball_on_relief));
      std::string cells;
      for (std::size_t k = 0; k < r.change.size(); ++k) cells += bench::fmt("%s%.6g", k ? ", " : "", r.change[k]);
      j += bench::fmt("    {\"read\": \"%s\", \"what\": \"%s\", \"step_s\": %g, \"mean\": %.6g, \"deviation\": %.6g, "
                      "\"neighbour_correlation\": %s, \"difference_from_prediction_0_1ms\": {\"mean\": %.6g, "
                      "\"standard_error\": %.6g, \"neighbour_correlation\": %s}, \"period_change\": [%s]}%s\n",
                      r.ball_on_relief ? "ball on relief" : "one point", r.predicted ? "predicted" : "simulated", r.step_s, r.mean(),
                      r.deviation(), correlation(r.change).c_str(), ReleaseRow::mean(d), standardError(d), correlation(d).c_str(),
                      cells.c_str(), i + 1 < many.size() ? "," : "");
    }
    j += "  ]}\n}\n";
    bench::writeTextFile(json, j);
  }
  if (!md.empty()) {
    std::string t = "Measured " + stamp + ". A 1 cm, 50 g ball, 1 ms steps, UV spheres of radius 10 cm (N segments, N/2 rings). ";
    t += bench::fmt("Bowl: released 5° up the inside, period against 2π √(7 (R − r) / 5g) = %.5f s. Roll-off: from rest 1° off "
                    "the top, friction 10, where it leaves against cos θ = 10/17 cos 1° (%.2f°). Smooth: the contacts steered by "
                    "the smooth surface (the default); flat: Bullet's own on the triangles.\n\n",
                    period, leave);
    t += "| segments | triangles | bowl period, smooth | flat | roll-off, smooth | flat | µs per step, smooth | flat |\n"
         "|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    for (const Row& r : rows) {
      auto angle = [](bool left, double e) { return left ? bench::fmt("%+.2f°", e) : std::string("stayed on"); };
      t += bench::fmt("| %d | %zu | %+.2f %% | %+.2f %% | %s | %s | %.1f | %.1f |\n", r.segments, r.triangles,
                      100 * r.period_smooth, 100 * r.period_flat, angle(r.left_smooth, r.leave_smooth).c_str(),
                      angle(r.left_flat, r.leave_flat).c_str(), r.us_smooth, r.us_flat);
    }
    t += bench::fmt("\nWith a fine texture (%d segments, smooth contact): sine bumps 2.5 mm apart, steepest slope s, against the "
                    "same scene untextured. The bowl's period: simulated, and predicted from the texture's slopes (read at the "
                    "foot as the contact reads them; the rolling integrated without Bullet); at the pole the bottom is the UV "
                    "sphere's pole (the uv squeezes the texture there), on the equator the sphere is turned so the texture "
                    "lies under the swing at its stated scale.\n\n",
                    texture_segments);
    t += "| slope s | atan s | roll-off: departure moved | bowl at the pole: period changed | predicted | periods "
         "| bowl on the equator: period changed | predicted | periods |\n|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    for (const TexturedRow& r : textured)
      t += bench::fmt("| %g | %.2f° | %s | %+.2f %% | %+.2f %% | %d | %+.2f %% | %+.2f %% | %d |\n", r.slope,
                      std::atan(r.slope) * 180.0 / kPi,
                      r.left ? bench::fmt("%+.2f°", r.leave_change_deg).c_str() : "stayed on", 100 * r.pole.simulated,
                      100 * r.pole.predicted, r.pole.periods, 100 * r.equator.simulated, 100 * r.equator.predicted,
                      r.equator.periods);
    t += "\nThe same bumps as a relief (depth 2a) met as the ball's sphere meets it (`ballOnReliefNormal`), in the "
         "simulation and in the prediction; and the cost of a step (one ball) read each way.\n\n";
    t += "| slope s | bowl at the pole: period changed | predicted | periods | bowl on the equator: period changed | predicted "
         "| periods | µs per step, one point: pole | equator | ball on relief: pole | equator |\n"
         "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    for (const TexturedRow& r : textured)
      t += bench::fmt("| %g | %+.2f %% | %+.2f %% | %d | %+.2f %% | %+.2f %% | %d | %.1f | %.1f | %.1f | %.1f |\n", r.slope,
                      100 * r.pole_relief.simulated, 100 * r.pole_relief.predicted, r.pole_relief.periods,
                      100 * r.equator_relief.simulated, 100 * r.equator_relief.predicted, r.equator_relief.periods,
                      r.pole.us_per_step, r.equator.us_per_step, r.pole_relief.us_per_step, r.equator_relief.us_per_step);
    t += "\nReleased a little higher or lower (the bottom on the equator): the period's change simulated / predicted at each "
         "release, how many releases agree within 1 point (1 % of the period), and the mean over the releases.\n\n";
    // A table with a column per release between `first` and `last` columns (each given with its
    // separators and the row of alignments that follows them).
    auto byRelease = [](const char* first, const char* last, const char* last_alignment) {
      std::string h = first;
      for (double deg : kReleasesDeg) h += bench::fmt(" %.2f° |", deg);
      h += std::string(last) + "\n|---:|---|";
      for (std::size_t k = 0; k < std::size(kReleasesDeg); ++k) h += "---:|";
      return h + last_alignment + "\n";
    };
    t += byRelease("| slope s | read |", " within 1 point | mean: simulated | predicted |", "---:|---:|---:|");
    for (const ReleaseRow& r : releases) {
      t += bench::fmt("| %g | %s |", r.slope, r.ball_on_relief ? "ball on relief" : "one point");
      for (std::size_t k = 0; k < r.simulated.size(); ++k) t += bench::fmt(" %+.2f / %+.2f %% |", 100 * r.simulated[k], 100 * r.predicted[k]);
      t += bench::fmt(" %d of %zu | %+.2f %% | %+.2f %% |\n", r.within(0.01), r.simulated.size(), 100 * ReleaseRow::mean(r.simulated),
                      100 * ReleaseRow::mean(r.predicted));
    }
    t += bench::fmt("\nThe relief's rows (ball on relief, the bottom on the equator) by step: simulated at 1, 0.5, 0.25 and 0.1 ms "
                    "(the untextured swing at the same step the reference of each), and predicted at %g ms besides the 0.1 ms of the "
                    "tables above; how many releases agree within 1 point with the 0.1 ms prediction, and the wall clock a "
                    "simulated second costs (one ball).\n\n",
                    kFinePredictionStepS * 1e3);
    t += byRelease("| slope s | step |", " within 1 point of the 0.1 ms prediction | wall clock per simulated second |", "---:|---:|");
    for (const StepRow& r : steps) {
      t += bench::fmt("| %g | %s %g ms |", r.slope, r.predicted ? "predicted at" : "simulated at", r.step_s * 1e3);
      for (double x : r.change) t += bench::fmt(" %+.2f %% |", 100 * x);
      t += bench::fmt(" %d of %zu | %s |\n", agreeing(r.change, reference(r.slope), 0.01), r.change.size(),
                      std::isfinite(r.wall_per_simulated) ? bench::fmt("%.2f s", r.wall_per_simulated).c_str() : "");
    }
    t += bench::fmt("\nAt s = %g, %d releases evenly over %.2f° to %.2f° (the bottom on the equator): the period's change "
                    "simulated and predicted at two steps each, its mean and standard deviation over the releases, and the "
                    "correlation of each release's change with the next one's; then, release by release, the change less the "
                    "0.1 ms prediction of the same read: its mean ± its standard error (as if the releases were independent), "
                    "the same correlation of neighbours for it, and how many releases agree with that prediction within 1 "
                    "point.\n\n",
                    kManySlope, many_releases, manyRelease(0, many_releases), manyRelease(many_releases - 1, many_releases));
    t += "| read | step | mean change | standard deviation | neighbours' correlation | less the 0.1 ms prediction | its "
         "neighbours' correlation | within 1 point of it |\n|---|---|---:|---:|---:|---:|---:|---:|\n";
    for (const ManyRow& r : many) {
      const ManyRow& prediction = manyReference(r.ball_on_relief);
      const std::vector<double> d = r.differenceFrom(prediction);
      const bool self = &r == &prediction;
      t += bench::fmt("| %s | %s %g ms | %+.2f %% | %.2f points | %.2f | %s | %s | %d of %zu |\n",
                      r.ball_on_relief ? "ball on relief" : "one point", r.predicted ? "predicted at" : "simulated at", r.step_s * 1e3,
                      100 * r.mean(), 100 * r.deviation(), neighbourCorrelation(r.change),
                      self ? "" : bench::fmt("%+.2f ± %.2f points", 100 * ReleaseRow::mean(d), 100 * standardError(d)).c_str(),
                      self ? "" : bench::fmt("%.2f", neighbourCorrelation(d)).c_str(), agreeing(r.change, prediction.change, 0.01),
                      r.change.size());
    }
    bench::writeTextFile(md, t);
  }
  if (!png.empty()) {
    bench::PlotPanel period_panel, leave_panel, cost_panel;
    period_panel.title = "Bowl: swing period error", period_panel.x_label = "triangles", period_panel.y_label = "|error| %";
    leave_panel.title = "Roll-off: departure angle error", leave_panel.x_label = "triangles", leave_panel.y_label = "|error| degrees";
    cost_panel.title = "Cost of a step (one ball)", cost_panel.x_label = "triangles", cost_panel.y_label = "microseconds per step";
    auto series = [](const char* label, bench::Rgb color, bench::Marker marker) {
      bench::PlotSeries s;
      s.label = label, s.color = color, s.marker = marker;
      return s;
    };
    bench::PlotSeries ps = series("smooth contact", {60, 120, 200}, bench::Marker::Circle),
                      pf = series("flat triangles (Bullet)", {200, 60, 40}, bench::Marker::Square);
    bench::PlotSeries ls = ps, lf = pf, cs = ps, cf = pf;
    double e_min = 1e9, e_max = 0, a_min = 1e9, a_max = 0, c_min = 1e9, c_max = 0;
    for (const Row& r : rows) {
      const double x = double(r.triangles);
      // Log axes: an error of exactly zero is drawn at the axis floor.
      const double es = std::max(1e-3, 100 * std::fabs(r.period_smooth)), ef = std::max(1e-3, 100 * std::fabs(r.period_flat));
      const double as = std::max(1e-2, std::fabs(r.leave_smooth)), af = std::max(1e-2, std::fabs(r.leave_flat));
      if (std::isfinite(es)) ps.x.push_back(x), ps.y.push_back(es), e_min = std::min(e_min, es), e_max = std::max(e_max, es);
      if (std::isfinite(ef)) pf.x.push_back(x), pf.y.push_back(ef), e_min = std::min(e_min, ef), e_max = std::max(e_max, ef);
      if (r.left_smooth) ls.x.push_back(x), ls.y.push_back(as), a_min = std::min(a_min, as), a_max = std::max(a_max, as);
      if (r.left_flat) lf.x.push_back(x), lf.y.push_back(af), a_min = std::min(a_min, af), a_max = std::max(a_max, af);
      cs.x.push_back(x), cs.y.push_back(r.us_smooth), cf.x.push_back(x), cf.y.push_back(r.us_flat);
      c_min = std::min({c_min, r.us_smooth, r.us_flat}), c_max = std::max({c_max, r.us_smooth, r.us_flat});
    }
    period_panel.series = {ps, pf};
    leave_panel.series = {ls, lf};
    cost_panel.series = {cs, cf};
    for (bench::PlotPanel* p : {&period_panel, &leave_panel, &cost_panel}) {
      p->x_min = double(rows.front().triangles) / 1.5, p->x_max = double(rows.back().triangles) * 1.5;
    }
    period_panel.y_min = e_min / 2, period_panel.y_max = e_max * 2;
    leave_panel.y_min = a_min / 2, leave_panel.y_max = a_max * 2;
    cost_panel.y_min = c_min / 1.5, cost_panel.y_max = c_max * 1.5;
    bench::writePlotPng(png, {period_panel, leave_panel, cost_panel},
                        "bench_physics_mesh: balls on tessellated spheres, speed against error (" + stamp + ")", 520, 460);
  }
  for (const Row& r : rows)
    std::printf("%4d segments %6zu triangles: bowl %+.2f %% (flat %+.2f %%), roll-off %+.2f deg (flat %+.2f deg), %.1f us/step\n",
                r.segments, r.triangles, 100 * r.period_smooth, 100 * r.period_flat, r.leave_smooth, r.leave_flat, r.us_smooth);
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return bench::benchMain(argc, argv, kHelp, "bench_physics_mesh", run); }
