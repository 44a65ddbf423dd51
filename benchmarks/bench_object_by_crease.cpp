// A block by a crease of a mesh (issue 29; docs/physics.md "Across a crease"): a plain block and a
// grooved one on a slab mesh's top, far from its edge, just short of it and past it
// (tests/physics/crease_scene.hpp), on the grooved slab, on the untextured slab's smooth chart and
// on Bullet's triangles. Where it rests, how it tips over the edge against a block pivoting on it
// without slipping, and the cost of a step: what each surface across the crease on a chart of its
// own costs. Measures only; nothing asserted (tests/physics/test_object_across_a_crease.cpp holds
// the behaviour).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "benchmarks/bench_help.hpp"
#include "benchmarks/bench_rig.hpp"
#include "benchmarks/bench_stamp.hpp"
#include "tests/physics/crease_scene.hpp"

namespace {

using namespace thx;
using namespace thx::phys::test::crease;

constexpr const char* kHelp = R"(usage: bench_object_by_crease [--json F] [--csv F] [--md F]

A 2 x 2 x 1 cm, 50 g block (friction 0.3) on the top of a slab mesh whose top carries V-grooves
(4 mm apart, 1 mm deep, 128 texels over 4 cm, a ridge on the slab's edge), or on the same slab
untextured (met on its smooth chart, or on Bullet's triangles). The block is plain (resting on
the ridges) or grooved like the slab (its ridges down in the slab's grooves). Its centre is put
3 cm short of the edge (no crease within its reach), just short of it (3 mm for the plain block,
2 mm for the grooved one) or as far past it. At 1 ms steps:
  - short of the edge it is left 0.3 s: how far it settled, and how far it moved from 0.1 s on;
  - past the edge it is left 60 ms: its pitch at 30 and 60 ms, against the plain block pivoting
    from rest on the edge without slipping, and its fastest speed along x.
The time per step is the run's wall clock over its steps (one run each; the machine is shared:
compare within a run).

  --json/--csv/--md F   results
)";

const char* const kGroundNames[] = {"grooved slab", "untextured, smooth chart", "untextured, Bullet's triangles"};
constexpr Ground kGrounds[] = {Ground::Grooved, Ground::Smooth, Ground::Triangles};
enum class Place { Far, Short, Past };
const char* const kPlaceNames[] = {"3 cm short", "short", "past"};

struct Row {
  bool grooved_block = false;
  int ground = 0;
  Place place = Place::Far;
  double beyond_m = 0;
  Tip tip;
  double pivot30 = 0, pivot60 = 0;  // the plain block's pivot (past only)
  double us_per_step = 0;
};

std::string placeName(const Row& r) {
  return r.place == Place::Far ? kPlaceNames[0] : bench::fmt("%.0f mm %s", std::fabs(r.beyond_m) * 1e3, kPlaceNames[int(r.place)]);
}

int run(int argc, char** argv) {
  const bench::ResultFiles files = bench::resultFilesOnly(argc, argv);
  const std::string &json = files.json, &csv = files.csv, &md = files.md;
  std::vector<Row> rows;
  for (bool grooved : {false, true}) {
    for (int g = 0; g < 3; ++g) {
      for (Place place : {Place::Far, Place::Short, Place::Past}) {
        Row row;
        row.grooved_block = grooved, row.ground = g, row.place = place;
        const double near = grooved ? 0.002 : 0.003;
        row.beyond_m = place == Place::Far ? -0.03 : place == Place::Short ? -near : near;
        std::fprintf(stderr, "bench_object_by_crease: %s block on the %s, %s ...\n", grooved ? "grooved" : "plain",
                     kGroundNames[g], placeName(row).c_str());
        CreaseScene scene(row.beyond_m, kGrounds[g], grooved);
        const double seconds = place == Place::Past ? 0.06 : 0.3;
        const auto t0 = std::chrono::steady_clock::now();
        row.tip = scene.run(seconds);
        const auto t1 = std::chrono::steady_clock::now();
        row.us_per_step = std::chrono::duration<double, std::micro>(t1 - t0).count() / (seconds / kDt);
        if (place == Place::Past) row.pivot30 = pivotPitch(row.beyond_m, 0.03), row.pivot60 = pivotPitch(row.beyond_m, 0.06);
        rows.push_back(row);
      }
    }
  }
  const std::string stamp = bench::fmt("%s, %s build, %s", bench::isoNow().c_str(), bench::buildType(),
                                       bench::machineSummary().c_str());
  auto block = [](const Row& r) { return r.grooved_block ? "grooved" : "plain"; };
  if (!csv.empty()) {
    std::string c = "block,ground,place,beyond_m,moved_um,drift_um,pitch_30ms,pitch_60ms,pivot_30ms,pivot_60ms,fastest_x,us_per_step\n";
    for (const Row& r : rows)
      c += bench::fmt("%s,%s,%s,%.4f,%.2f,%.3f,%.4f,%.4f,%.4f,%.4f,%.4f,%.2f\n", block(r), kGroundNames[r.ground],
                      kPlaceNames[int(r.place)], r.beyond_m, r.tip.moved_m * 1e6, r.tip.drift_m * 1e6, r.tip.pitch_30ms,
                      r.tip.pitch_60ms, r.pivot30, r.pivot60, r.tip.fastest_x, r.us_per_step);
    bench::writeTextFile(csv, c);
  }
  if (!json.empty()) {
    std::string j = bench::fmt("{\"stamp\": \"%s\", \"rows\": [", stamp.c_str());
    for (std::size_t k = 0; k < rows.size(); ++k) {
      const Row& r = rows[k];
      j += bench::fmt("%s{\"block\": \"%s\", \"ground\": \"%s\", \"place\": \"%s\", \"beyond_m\": %.4f, "
                      "\"moved_um\": %.3f, \"drift_um\": %.4f, \"pitch_30ms\": %.5f, \"pitch_60ms\": %.5f, "
                      "\"pivot_30ms\": %.5f, \"pivot_60ms\": %.5f, \"fastest_x\": %.5f, \"us_per_step\": %.3f}",
                      k ? ", " : "", block(r), kGroundNames[r.ground], kPlaceNames[int(r.place)], r.beyond_m,
                      r.tip.moved_m * 1e6, r.tip.drift_m * 1e6, r.tip.pitch_30ms, r.tip.pitch_60ms, r.pivot30,
                      r.pivot60, r.tip.fastest_x, r.us_per_step);
    }
    bench::writeTextFile(json, j + "]}\n");
  }
  if (!md.empty()) {
    std::string t = "Measured " + stamp +
                    ". Short of the edge: how far the block settled in 0.3 s and moved from 0.1 s on. Past it: its "
                    "pitch at 30 and 60 ms (the plain block pivoting on the edge without slipping in brackets) and "
                    "its fastest speed along x. The time per step over the run.\n\n"
                    "| block | slab | centre | settled | then moved | pitch 30 ms | pitch 60 ms | fastest | step |\n"
                    "|---|---|---|---:|---:|---:|---:|---:|---:|\n";
    for (const Row& r : rows) {
      if (r.place == Place::Past) {
        const std::string pivot30 = r.grooved_block ? "" : bench::fmt(" (%.3f)", r.pivot30);
        const std::string pivot60 = r.grooved_block ? "" : bench::fmt(" (%.3f)", r.pivot60);
        t += bench::fmt("| %s | %s | %s | | | %.3f%s | %.3f%s | %.2f m/s | %.0f µs |\n", block(r), kGroundNames[r.ground],
                        placeName(r).c_str(), r.tip.pitch_30ms, pivot30.c_str(), r.tip.pitch_60ms, pivot60.c_str(),
                        r.tip.fastest_x, r.us_per_step);
      } else {
        t += bench::fmt("| %s | %s | %s | %.1f µm | %.2f µm | | | | %.0f µs |\n", block(r), kGroundNames[r.ground],
                        placeName(r).c_str(), r.tip.moved_m * 1e6, r.tip.drift_m * 1e6, r.us_per_step);
      }
    }
    bench::writeTextFile(md, t);
  }
  for (const Row& r : rows)
    std::printf("%s block, %s, %s: moved %.1f um (then %.2f um), pitch %.3f/%.3f (pivot %.3f/%.3f), fastest %.2f m/s, "
                "%.0f us/step\n",
                block(r), kGroundNames[r.ground], placeName(r).c_str(), r.tip.moved_m * 1e6, r.tip.drift_m * 1e6,
                r.tip.pitch_30ms, r.tip.pitch_60ms, r.pivot30, r.pivot60, r.tip.fastest_x, r.us_per_step);
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return bench::benchMain(argc, argv, kHelp, "bench_object_by_crease", run); }
