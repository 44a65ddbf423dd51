// A rod in a V-groove (issue 29; docs/physics.md "Plain objects on a relief mesh"): a capsule, a
// cylinder and a ball of their radius lying along a groove on the relief plane, on a flat relief
// mesh, on a pipe's grooved inside and on a textured box's top face
// (tests/physics/rod_in_groove_scene.hpp), against the analytic answers: where it rests, and the
// horizontal force that rolls it out of the groove; with the cost of a step. Measures only;
// nothing asserted (tests/physics/test_plain_objects_on_relief_mesh.cpp and
// test_ball_in_v_groove.cpp hold the behaviour).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <string>
#include <vector>

#include "base/cli_number.hpp"
#include "base/error.hpp"
#include "benchmarks/bench_help.hpp"
#include "benchmarks/bench_rig.hpp"
#include "benchmarks/bench_stamp.hpp"
#include "tests/physics/rod_in_groove_scene.hpp"

namespace {

using namespace thx;
using namespace thx::phys::test::rod_in_groove;

constexpr const char* kHelp = R"(usage: bench_rod_in_groove [--texels N,N,...] [--json F] [--csv F] [--md F]

A capsule and a cylinder (3 mm radius, 2 cm long, 20 g, friction 0.3) lying along a V-groove, and
a plain ball of their radius and mass (their cross-section: the same answers; on the meshes met
as physics-client meets a ball, lifted onto the relief as its sphere meets it)
(grooves 4 mm apart and 1 mm deep, walls at theta = 26.57 degrees; a relief of N texels over
4 cm) on the relief plane, on the same relief laid on a flat box mesh, on the inside of a
pipe of radius 10.2 cm whose grooves run along its axis (the rod 2 mm from its bottom line, where
the bend raises the groove's floor 19 um), and on the top face of a fixed box (0.2 x 0.2 x 0.02 m)
whose faces carry the relief (the capsule met as the balls on its segment, the cylinder by the
rod rules on the face's chart: clients/physics/box_ground.hpp). At 1 ms steps it settles 0.5 s; where it rests is
compared with its circle touching both walls, its axis r / cos(theta) - D above the ridges (plus
the bend in the pipe). Then a horizontal force across the grooves, applied at its centre for
0.3 s, rolls it out when it exceeds tan(theta) = 0.5 of its weight (in the pipe, tan of theta
plus the bend's slope where the far wall touches it): the smallest force that moves
it more than half a period is bisected to 0.005 in [0, 1]. The time per step is that of the 0.3 s
pushed at 0.4 of its weight (in the groove, against its wall).

  --texels LIST   relief sizes over 4 cm (default 128,256)
  --json/--csv/--md F   results
)";

constexpr Ground kGrounds[] = {Ground::Plane, Ground::FlatMesh, Ground::Trough, Ground::Box};
const char* const kGroundNames[] = {"relief plane", "flat mesh", "pipe", "grooved box"};
constexpr int kGroundCount = int(std::size(kGrounds));
constexpr Rod kRods[] = {Rod::Capsule, Rod::LyingCylinder, Rod::Ball};
const char* const kRodNames[] = {"capsule", "cylinder", "ball"};
constexpr int kRodCount = int(std::size(kRods));
constexpr double kPushS = 0.3;

struct Row {
  int texels = 0;
  int ground = 0, rod = 0;
  double rest_error_um = 0;  // above the analytic rest height
  double breakaway = 0;      // force over weight
  double law = 0;            // tan of the far wall's angle (in the pipe, plus the bend's slope there)
  double us_per_step = 0;
};

double breakaway(Ground ground, Rod rod, int texels) {
  double lo = 0.0, hi = 1.0;
  while (hi - lo > 0.005) {
    const double mid = 0.5 * (lo + hi);
    RodScene s(ground, rod, texels);
    (s.push(mid, kPushS).x() > 0.5 * kPeriod ? hi : lo) = mid;
  }
  return 0.5 * (lo + hi);
}

int run(int argc, char** argv) {
  std::vector<int> texels{128, 256};
  std::string json, csv, md;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (i + 1 >= argc) throw UsageError(a + " needs a value (see --help)");
    const std::string v = argv[++i];
    if (a == "--texels") texels = cli::parseIntegerList(a, v, 16, 2048);
    else if (a == "--json") json = v;
    else if (a == "--csv") csv = v;
    else if (a == "--md") md = v;
    else throw UsageError("unknown option " + a + " (see --help)");
  }
  std::vector<Row> rows;
  for (int n : texels) {
    for (int g = 0; g < kGroundCount; ++g) {
      for (int r = 0; r < kRodCount; ++r) {
        std::fprintf(stderr, "bench_rod_in_groove: %d texels, %s on the %s ...\n", n, kRodNames[r], kGroundNames[g]);
        Row row;
        row.texels = n, row.ground = g, row.rod = r;
        RodScene s(kGrounds[g], kRods[r], n);
        const double bend = kGrounds[g] == Ground::Trough ? 0.5 * s.rest.x() * s.rest.x() / kTroughRadius : 0.0;
        row.rest_error_um = (s.rest.z() - inTheGroove(kRadius) - bend) * 1e6;
        // The far wall touches the rod r sin(theta) beyond its axis; in the pipe the bend tilts it
        // further by its slope there.
        const double far = s.rest.x() + kRadius * std::sin(kWall);
        row.law = std::tan(kWall + (kGrounds[g] == Ground::Trough ? std::atan(far / kTroughRadius) : 0.0));
        const auto t0 = std::chrono::steady_clock::now();
        s.push(0.4, kPushS);
        const auto t1 = std::chrono::steady_clock::now();
        row.us_per_step = std::chrono::duration<double, std::micro>(t1 - t0).count() / (kPushS / kDt);
        row.breakaway = breakaway(kGrounds[g], kRods[r], n);
        rows.push_back(row);
      }
    }
  }
  const std::string stamp = bench::fmt("%s, %s build, %s", bench::isoNow().c_str(), bench::buildType(),
                                       bench::machineSummary().c_str());
  if (!csv.empty()) {
    std::string c = "texels,ground,rod,rest_error_um,breakaway,law,us_per_step\n";
    for (const Row& r : rows)
      c += bench::fmt("%d,%s,%s,%.2f,%.4f,%.4f,%.2f\n", r.texels, kGroundNames[r.ground], kRodNames[r.rod],
                      r.rest_error_um, r.breakaway, r.law, r.us_per_step);
    bench::writeTextFile(csv, c);
  }
  if (!json.empty()) {
    std::string j = bench::fmt("{\"stamp\": \"%s\", \"rows\": [", stamp.c_str());
    for (std::size_t k = 0; k < rows.size(); ++k) {
      const Row& r = rows[k];
      j += bench::fmt("%s{\"texels\": %d, \"ground\": \"%s\", \"rod\": \"%s\", \"rest_error_um\": %.3f, "
                      "\"breakaway\": %.5f, \"law\": %.5f, \"us_per_step\": %.3f}",
                      k ? ", " : "", r.texels, kGroundNames[r.ground], kRodNames[r.rod], r.rest_error_um, r.breakaway,
                      r.law, r.us_per_step);
    }
    bench::writeTextFile(json, j + "]}\n");
  }
  if (!md.empty()) {
    std::string t = "Measured " + stamp +
                    ". Rest: the axis above r / cos(theta) - D (plus the bend in the pipe); the force that rolls it "
                    "out, over its weight, against tan of the far wall's angle (theta; in the pipe plus the bend's "
                    "slope there); the time per step.\n\n"
                    "| texels | ground | rod | rest | force | wall's tan | step |\n|---:|---|---|---:|---:|---:|---:|\n";
    for (const Row& r : rows)
      t += bench::fmt("| %d | %s | %s | %+.1f µm | %.3f | %.3f | %.0f µs |\n", r.texels, kGroundNames[r.ground],
                      kRodNames[r.rod], r.rest_error_um, r.breakaway, r.law, r.us_per_step);
    bench::writeTextFile(md, t);
  }
  for (const Row& r : rows)
    std::printf("%d texels, %s, %s: rest %+.1f um, force %.3f (wall %.3f), %.0f us/step\n", r.texels,
                kGroundNames[r.ground], kRodNames[r.rod], r.rest_error_um, r.breakaway, r.law, r.us_per_step);
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return bench::benchMain(argc, argv, kHelp, "bench_rod_in_groove", run); }
