// Two textured bodies (issue 29; docs/physics.md "Textured objects"): a grooved block on a
// grooved plane (tests/physics/grooved_block_scene.hpp) pushed sideways by a horizontal force
// raised slowly (and, across, also applied at once); the force that starts it sliding, found by
// bisection, along the grooves and across them,
// against the wedge's answers (friction alone along; tan(wall + atan(mu)) across), in both orders
// of the pair and beside a plain block; and the cost of a step, by texture size. Measures only;
// nothing asserted (tests/physics/test_textured_box.cpp holds the behaviour).
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
#include "tests/physics/grooved_block_scene.hpp"

namespace {

using namespace thx;
using namespace thx::phys::test::grooved_block;

constexpr const char* kHelp = R"(usage: bench_textured_pair [--texels N,N,...] [--quick] [--json F] [--csv F] [--md F]

A 2 x 2 x 1 cm, 50 g block (friction 0.3) on a relief plane of V-grooves along y, 4 mm apart
and 1 mm deep (walls at 26.6 degrees); the block's faces carry the same relief, set half a period
over so its ridges sit in the plane's grooves (clients/physics/textured_box.hpp), or none (a
plain block). At 1 ms steps the block settles for 0.1 s, then a horizontal force pushes it,
raised from zero over 0.5 s and held for 0.3 s (so the block is not thrown up the walls by its
own momentum); it slides when its centre moves 1 mm along the push. The smallest force that
slides it, over its weight, is bisected to 0.004 in [0, 2]: along the grooves, across them,
across with the pair handed to the relief algorithm in the other order (the block added to the
world first), a plain block across, and the grooved block across under the force applied at
once and held for 0.3 s; then along and across with the same grooves laid on a flat slab
mesh's top (met on its relief chart) instead of the plane, and on the faces of a fixed
20 x 20 x 2 cm box (clients/physics/box_ground.hpp; across also with the box a 1 kg body on a
plain plane). Against: friction alone along (0.3)
and for the plain block;
across, up a wall with friction, tan(26.57 + 16.70 deg) = 0.942. Then the mean wall-clock time
of a step while pushed along, textured and plain, and textured on the fixed box. Each texture
size N texels over 4 cm.

  --texels LIST   texture sizes (default 64,128,256)
  --quick         64 and 128 only
  --json/--csv/--md F   results
)";

constexpr double kRampS = 0.5, kPushS = 0.3, kSlidesM = 1e-3;

struct Row {
  int texels = 0;
  double along = 0, across = 0, across_swapped = 0, plain_across = 0;  // force over weight, raised slowly
  double across_at_once = 0;                                            // applied at once
  double along_mesh = 0, across_mesh = 0;  // raised slowly, the grooves on a flat slab mesh's top
  double along_box = 0, across_box = 0, across_moving_box = 0;  // the grooves on a box's faces
  double us_textured = 0, us_plain = 0, us_box = 0;                    // per step
};

double breakaway(int texels, bool textured, bool block_first, const Eigen::Vector3d& direction, double ramp_s = kRampS,
                 BlockGround ground = BlockGround::Plane) {
  double lo = 0.0, hi = 2.0;
  while (hi - lo > 0.004) {
    const double mid = 0.5 * (lo + hi);
    Scene s(textured, block_first, texels, {}, ground);
    const double moved = s.push(mid * direction, kPushS, ramp_s).dot(direction);
    (moved >= kSlidesM ? hi : lo) = mid;
  }
  return 0.5 * (lo + hi);
}

double microsPerStep(int texels, bool textured, BlockGround ground = BlockGround::Plane) {
  Scene s(textured, false, texels, {}, ground);
  const auto t0 = std::chrono::steady_clock::now();
  s.push({0.0, 0.5, 0.0}, kPushS);
  const auto t1 = std::chrono::steady_clock::now();
  return std::chrono::duration<double, std::micro>(t1 - t0).count() / (kPushS / kDt);
}

int run(int argc, char** argv) {
  std::vector<int> texels{64, 128, 256};
  std::string json, csv, md;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--quick") {
      texels = {64, 128};
      continue;
    }
    if (i + 1 >= argc) throw UsageError(a + " needs a value (see --help)");
    const std::string v = argv[++i];
    if (a == "--texels") texels = cli::parseIntegerList(a, v, 16, 1024);
    else if (a == "--json") json = v;
    else if (a == "--csv") csv = v;
    else if (a == "--md") md = v;
    else throw UsageError("unknown option " + a + " (see --help)");
  }
  const Eigen::Vector3d x = Eigen::Vector3d::UnitX(), y = Eigen::Vector3d::UnitY();
  std::vector<Row> rows;
  for (int n : texels) {
    std::fprintf(stderr, "bench_textured_pair: %d texels ...\n", n);
    Row r;
    r.texels = n;
    r.along = breakaway(n, true, false, y);
    r.across = breakaway(n, true, false, x);
    r.across_swapped = breakaway(n, true, true, x);
    r.plain_across = breakaway(n, false, false, x);
    r.across_at_once = breakaway(n, true, false, x, 0.0);
    r.along_mesh = breakaway(n, true, false, y, kRampS, BlockGround::SlabMesh);
    r.across_mesh = breakaway(n, true, false, x, kRampS, BlockGround::SlabMesh);
    r.along_box = breakaway(n, true, false, y, kRampS, BlockGround::FixedBox);
    r.across_box = breakaway(n, true, false, x, kRampS, BlockGround::FixedBox);
    r.across_moving_box = breakaway(n, true, false, x, kRampS, BlockGround::MovingBox);
    r.us_textured = microsPerStep(n, true);
    r.us_plain = microsPerStep(n, false);
    r.us_box = microsPerStep(n, true, BlockGround::FixedBox);
    rows.push_back(r);
  }
  const std::string stamp = bench::fmt("%s, %s build, %s", bench::isoNow().c_str(), bench::buildType(),
                                       bench::machineSummary().c_str());
  if (!csv.empty()) {
    std::string c = "texels,texel_mm,along,across,across_other_order,plain_across,across_at_once,along_slab_mesh,"
                    "across_slab_mesh,along_box,across_box,across_moving_box,expected_along,expected_across,us_per_step_textured,"
                    "us_per_step_plain,us_per_step_on_box\n";
    for (const Row& r : rows)
      c += bench::fmt("%d,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.2f,%.2f,%.2f\n", r.texels,
                      1e3 * kExtent / r.texels, r.along, r.across, r.across_swapped, r.plain_across, r.across_at_once,
                      r.along_mesh, r.across_mesh, r.along_box, r.across_box, r.across_moving_box, alongForce(),
                      acrossForce(), r.us_textured, r.us_plain, r.us_box);
    bench::writeTextFile(csv, c);
  }
  if (!json.empty()) {
    std::string j = bench::fmt("{\"stamp\": \"%s\", \"expected_along\": %.6f, \"expected_across\": %.6f, \"rows\": [", stamp.c_str(),
                               alongForce(), acrossForce());
    for (std::size_t k = 0; k < rows.size(); ++k) {
      const Row& r = rows[k];
      j += bench::fmt("%s{\"texels\": %d, \"along\": %.6f, \"across\": %.6f, \"across_other_order\": %.6f, "
                      "\"plain_across\": %.6f, \"across_at_once\": %.6f, \"along_slab_mesh\": %.6f, "
                      "\"across_slab_mesh\": %.6f, \"along_box\": %.6f, \"across_box\": %.6f, "
                      "\"across_moving_box\": %.6f, \"us_per_step_textured\": %.3f, \"us_per_step_plain\": %.3f, "
                      "\"us_per_step_on_box\": %.3f}",
                      k ? ", " : "", r.texels, r.along, r.across, r.across_swapped, r.plain_across, r.across_at_once,
                      r.along_mesh, r.across_mesh, r.along_box, r.across_box, r.across_moving_box, r.us_textured,
                      r.us_plain, r.us_box);
    }
    bench::writeTextFile(json, j + "]}\n");
  }
  if (!md.empty()) {
    std::string t = "Measured " + stamp +
                    ". The force that starts the block sliding, over its weight (bisected to 0.004), raised over 0.5 s and held 0.3 s; "
                    "the last force column applied at once and held 0.3 s; expected " +
                    bench::fmt("%.3f along and %.3f across", alongForce(), acrossForce()) +
                    "; on a slab mesh: the same grooves laid on a flat mesh's top, met on its relief chart, raised slowly; "
                    "on a box: the same grooves on the faces of a fixed 20 x 20 x 2 cm box (moving: a 1 kg body on a plain "
                    "plane), raised slowly. "
                    "Time per step: the whole world's step while pushed along (on the plane, and on the fixed box).\n\n"
                    "| texels (texel) | along | across | across, other order | plain block across | across, at once | "
                    "along, slab mesh | across, slab mesh | along, box | across, box | across, moving box | "
                    "step, textured | step, plain | step, on a box |\n"
                    "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    for (const Row& r : rows)
      t += bench::fmt("| %d (%.3f mm) | %.3f | %.3f | %.3f | %.3f | %.3f | %.3f | %.3f | %.3f | %.3f | %.3f | %.0f µs | "
                      "%.0f µs | %.0f µs |\n",
                      r.texels, 1e3 * kExtent / r.texels, r.along, r.across, r.across_swapped, r.plain_across,
                      r.across_at_once, r.along_mesh, r.across_mesh, r.along_box, r.across_box, r.across_moving_box,
                      r.us_textured, r.us_plain, r.us_box);
    bench::writeTextFile(md, t);
  }
  for (const Row& r : rows)
    std::printf("%4d texels: along %.3f, across %.3f (other order %.3f), plain across %.3f, across at once %.3f; "
                "on a slab mesh along %.3f, across %.3f; on a box along %.3f, across %.3f (moving box %.3f); "
                "expected %.3f / %.3f; %.0f / %.0f / %.0f us per step\n",
                r.texels, r.along, r.across, r.across_swapped, r.plain_across, r.across_at_once, r.along_mesh, r.across_mesh,
                r.along_box, r.across_box, r.across_moving_box, alongForce(), acrossForce(), r.us_textured, r.us_plain,
                r.us_box);
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return bench::benchMain(argc, argv, kHelp, "bench_textured_pair", run); }
