// A ball with a bump map (issue 29; docs/physics.md "Textured objects"): on relief planes of 128,
// 256 and 512 texels over 4 cm, a uniformly recessed ball rolling down a virtual slope against
// rolling without slipping on its recessed radius, a bumpy ball let down on a flat and on a bumpy
// relief (how far its surface stands off the plane's relief at rest, found over the ball's own
// directions, and how still it lies), and the cost of a step rolling, beside a plain ball; and on
// UV-sphere meshes, where it meets the chart under it, a ball recessed 2 mm swinging in a smooth
// bowl and rolling off the top of a sphere against the rigid-ball answers for its recessed radius.
// Measures only; nothing asserted (tests/physics/test_textured_ball.cpp holds the behaviour).
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
#include "tests/physics/textured_ball_on_mesh_scene.hpp"
#include "tests/physics/textured_ball_scene.hpp"

namespace {

using namespace thx;
using namespace thx::phys;
using namespace thx::phys::test;
using namespace thx::phys::test::textured_ball;

constexpr const char* kHelp = R"(usage: bench_textured_ball [--texels N,N,...] [--segments N,N,...] [--json F] [--csv F] [--md F]

A 1 cm, 30 g ball whose bump map is laid on it as a cube projected onto the sphere, one tile
(pi r / 2 = 15.7 mm, 256 texels) per face (clients/physics/textured_ball.hpp), on a relief plane
of N texels over 4 cm, at 1 ms steps:
  rolling   every texel of the ball's map 0.5 mm deep, rolling from rest down a 5 degree virtual
            slope for 0.3 s: its speed against rolling without slipping on the recessed radius
            (a = g sin / (1 + 2 r^2 / (5 rho^2)), rho = r - 0.5 mm, the coarse ball's inertia)
  flat      bumps 3.9 mm apart, 0.3 mm high, on the ball, let down on a flat relief; after 4 s
            the gap between its surface and the plane's relief at its lowest, found over the
            ball's directions (negative: into it), and its fastest speed over the last 0.5 s
  bumpy     the same on a plane of bumps 2 mm apart, 0.4 mm high (tip on tip), after 3 s
  step      the mean wall-clock time of a step while the bumpy ball rolls at 0.1 m/s over the
            flat relief for 1 s, and a plain ball's
On UV spheres of N segments (meets the sphere on the chart under it; the ball's map 2 mm deep
everywhere, rho = 8 mm, k = 2 r^2 / (5 rho^2)):
  swing     released 5 degrees up the inside of a smooth 5 cm sphere, friction 1, 2.2 s: the
            period against 2 pi sqrt((R - rho)(1 + k) / g) (1 + theta0^2 / 16 + ...)
  leave     rolled from 5 degrees off the top of a 10 cm sphere, friction 10: where it leaves
            against cos(theta) = 2 cos(theta0) / (3 + k), on the smooth sphere and on a flat
            relief of 64 texels per 1 cm tile laid on it
  --texels LIST   plane texture sizes (default 128,256,512)
  --segments LIST UV sphere segments (default 64,128,256)
  --json/--csv/--md F   results
)";

struct Row {
  int texels = 0;
  double rolling_error = 0;                  // relative
  Settled flat, bumpy;
  double us_textured = 0, us_plain = 0;      // per step
};

struct MeshRow {
  int segments = 0;
  textured_ball_on_mesh::MeshRun swing, leave_smooth, leave_relief;
};

double microsPerStep(int texels, bool textured) {
  const tex::TextureMap map = bumpMap(3e-4);
  const FaceTexture texture = ballTexture(map);
  PhysicsWorld world;
  const SurfaceHolder plane = holdSurface(flatRelief(texels), 0.04, true);
  world.addReliefPlane(plane.surface, {0.5, 0.0, 0.0});
  btRigidBody& ball = textured ? world.addTexturedSphere(kRadius, kMass, at(0.0, 0.0, kRadius), {0.5, 0.0, 0.0}, texture)
                               : world.addSphere(kRadius, kMass, at(0.0, 0.0, kRadius), {0.5, 0.0, 0.0});
  setRolling(ball, 0.1, kRadius);
  const int steps = 1000;
  const auto t0 = std::chrono::steady_clock::now();
  for (int k = 0; k < steps; ++k) world.step(kDt);
  const auto t1 = std::chrono::steady_clock::now();
  return std::chrono::duration<double, std::micro>(t1 - t0).count() / steps;
}

int run(int argc, char** argv) {
  std::vector<int> texels{128, 256, 512}, segments{64, 128, 256};
  std::string json, csv, md;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (i + 1 >= argc) throw UsageError(a + " needs a value (see --help)");
    const std::string v = argv[++i];
    if (a == "--texels") texels = cli::parseIntegerList(a, v, 16, 2048);
    else if (a == "--segments") segments = cli::parseIntegerList(a, v, 16, 1024);
    else if (a == "--json") json = v;
    else if (a == "--csv") csv = v;
    else if (a == "--md") md = v;
    else throw UsageError("unknown option " + a + " (see --help)");
  }
  const double depth = 5e-4, slope = 5.0, seconds = 0.3, rho = kRadius - depth;
  const double expected = kG * std::sin(deg(slope)) / (1.0 + 0.4 * kRadius * kRadius / (rho * rho)) * seconds;
  const tex::TextureMap recess = uniformRecess(depth);
  const FaceTexture recessed = ballTexture(recess);
  std::vector<Row> rows;
  for (int n : texels) {
    std::fprintf(stderr, "bench_textured_ball: %d texels ...\n", n);
    Row r;
    r.texels = n;
    r.rolling_error = rollingSpeed(&recessed, slope, seconds, rho, n) / expected - 1.0;
    r.flat = settleBumpyBall(flatRelief(n), 4.0);
    r.bumpy = settleBumpyBall(bumpyPlane(n), 3.0);
    r.us_textured = microsPerStep(n, true);
    r.us_plain = microsPerStep(n, false);
    rows.push_back(r);
  }
  namespace on_mesh = textured_ball_on_mesh;
  const double swing_answer = on_mesh::recessedSwingAnswer(0.05, 5.0), leave_answer = on_mesh::recessedDepartureAnswer(5.0);
  const tex::TextureMap flat_tile = flatRelief(64);
  std::vector<MeshRow> mesh_rows;
  for (int n : segments) {
    std::fprintf(stderr, "bench_textured_ball: UV spheres of %d segments ...\n", n);
    MeshRow r;
    r.segments = n;
    r.swing = on_mesh::recessedSwing(0.05, 5.0, 2.2, n);
    r.leave_smooth = on_mesh::recessedDeparture(0.1, 5.0, nullptr, n);
    r.leave_relief = on_mesh::recessedDeparture(0.1, 5.0, &flat_tile, n);
    mesh_rows.push_back(r);
  }
  auto swingError = [&](const MeshRow& r) { return r.swing.value / swing_answer - 1.0; };
  const std::string stamp = bench::fmt("%s, %s build, %s", bench::isoNow().c_str(), bench::buildType(),
                                       bench::machineSummary().c_str());
  if (!csv.empty()) {
    std::string c = "texels,texel_mm,rolling_error,flat_gap_um,flat_fastest_mm_s,bumpy_gap_um,bumpy_fastest_mm_s,"
                    "us_per_step_textured,us_per_step_plain\n";
    for (const Row& r : rows)
      c += bench::fmt("%d,%.4f,%.6f,%.3f,%.4f,%.3f,%.4f,%.2f,%.2f\n", r.texels, 40.0 / r.texels, r.rolling_error,
                      r.flat.gap * 1e6, r.flat.fastest * 1e3, r.bumpy.gap * 1e6, r.bumpy.fastest * 1e3, r.us_textured,
                      r.us_plain);
    c += "\nsegments,triangles,swing_error,swing_us_per_step,leave_smooth_error_deg,leave_relief_error_deg,"
         "leave_smooth_us_per_step,leave_relief_us_per_step\n";
    for (const MeshRow& r : mesh_rows)
      c += bench::fmt("%d,%d,%.6f,%.1f,%.4f,%.4f,%.1f,%.1f\n", r.segments, r.segments * (r.segments / 2 - 1) * 2,
                      swingError(r), r.swing.us_per_step, r.leave_smooth.value - leave_answer,
                      r.leave_relief.value - leave_answer, r.leave_smooth.us_per_step, r.leave_relief.us_per_step);
    bench::writeTextFile(csv, c);
  }
  if (!json.empty()) {
    std::string j = bench::fmt("{\"stamp\": \"%s\", \"rows\": [", stamp.c_str());
    for (std::size_t k = 0; k < rows.size(); ++k) {
      const Row& r = rows[k];
      j += bench::fmt("%s{\"texels\": %d, \"rolling_error\": %.6f, \"flat_gap_um\": %.3f, \"flat_fastest_mm_s\": %.4f, "
                      "\"bumpy_gap_um\": %.3f, \"bumpy_fastest_mm_s\": %.4f, \"us_per_step_textured\": %.3f, "
                      "\"us_per_step_plain\": %.3f}",
                      k ? ", " : "", r.texels, r.rolling_error, r.flat.gap * 1e6, r.flat.fastest * 1e3, r.bumpy.gap * 1e6,
                      r.bumpy.fastest * 1e3, r.us_textured, r.us_plain);
    }
    j += "], \"mesh_rows\": [";
    for (std::size_t k = 0; k < mesh_rows.size(); ++k) {
      const MeshRow& r = mesh_rows[k];
      j += bench::fmt("%s{\"segments\": %d, \"swing_error\": %.6f, \"swing_us_per_step\": %.1f, "
                      "\"leave_smooth_error_deg\": %.4f, \"leave_relief_error_deg\": %.4f, \"leave_smooth_us_per_step\": %.1f, "
                      "\"leave_relief_us_per_step\": %.1f}",
                      k ? ", " : "", r.segments, swingError(r), r.swing.us_per_step, r.leave_smooth.value - leave_answer,
                      r.leave_relief.value - leave_answer, r.leave_smooth.us_per_step, r.leave_relief.us_per_step);
    }
    bench::writeTextFile(json, j + "]}\n");
  }
  if (!md.empty()) {
    std::string t = "Measured " + stamp +
                    ". Rolling: the recessed ball's speed after 0.3 s on the 5° virtual slope against rolling on its "
                    "recessed radius. Gap: its surface's lowest height over the plane's relief at rest (negative: "
                    "into it), found over the ball's directions; fastest: over the last 0.5 s. Step: the whole "
                    "world's step, rolling at 0.1 m/s on the flat relief.\n\n"
                    "| plane texels (texel) | rolling error | flat: gap | flat: fastest | bumpy: gap | bumpy: fastest | "
                    "step, bump-mapped ball | step, plain ball |\n"
                    "|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    for (const Row& r : rows)
      t += bench::fmt("| %d (%.3f mm) | %+.2f %% | %+.1f µm | %.2f mm/s | %+.1f µm | %.2f mm/s | %.1f µs | %.1f µs |\n",
                      r.texels, 40.0 / r.texels, 100.0 * r.rolling_error, r.flat.gap * 1e6, r.flat.fastest * 1e3,
                      r.bumpy.gap * 1e6, r.bumpy.fastest * 1e3, r.us_textured, r.us_plain);
    t += bench::fmt("\nOn UV spheres (the chart under the ball), the ball recessed 2 mm: the swing in a smooth 5 cm bowl "
                    "from 5° against %.4f s (a plain ball's answer %.4f s); leaving the top of a 10 cm sphere from 5° "
                    "against %.2f° (a plain ball's %.2f°); steps timed over each run.\n\n",
                    swing_answer, mesh_rolling::swingPeriodAt(0.05, 5.0), leave_answer, mesh_rolling::departureDeg(5.0));
    t += "| segments (triangles) | swing: period error | step | leaves, smooth | step | leaves, flat relief | step |\n"
         "|---:|---:|---:|---:|---:|---:|---:|\n";
    for (const MeshRow& r : mesh_rows)
      t += bench::fmt("| %d (%d) | %+.2f %% | %.0f µs | %+.2f° | %.0f µs | %+.2f° | %.0f µs |\n", r.segments,
                      r.segments * (r.segments / 2 - 1) * 2, 100.0 * swingError(r), r.swing.us_per_step,
                      r.leave_smooth.value - leave_answer, r.leave_smooth.us_per_step, r.leave_relief.value - leave_answer,
                      r.leave_relief.us_per_step);
    bench::writeTextFile(md, t);
  }
  for (const Row& r : rows)
    std::printf("%4d texels: rolling %+.2f %%; flat gap %+.1f um, fastest %.2f mm/s; bumpy gap %+.1f um, fastest %.2f "
                "mm/s; %.1f / %.1f us per step\n",
                r.texels, 100.0 * r.rolling_error, r.flat.gap * 1e6, r.flat.fastest * 1e3, r.bumpy.gap * 1e6,
                r.bumpy.fastest * 1e3, r.us_textured, r.us_plain);
  for (const MeshRow& r : mesh_rows)
    std::printf("%4d segments: swing %+.2f %% (%.0f us per step); leaves %+.2f deg smooth, %+.2f deg on a flat relief\n",
                r.segments, 100.0 * swingError(r), r.swing.us_per_step, r.leave_smooth.value - leave_answer,
                r.leave_relief.value - leave_answer);
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return bench::benchMain(argc, argv, kHelp, "bench_textured_ball", run); }
