// A ball with a bump map on ground with no features of its own, met on the ball's own texels
// (issue 29; clients/physics/ball_on_flat_ground.hpp; docs/physics.md "A ball with a bump map on
// flat ground"): the shipped dimpled ball let down at the bottom of a smooth bowl (a mesh's bent
// chart) from starts turned at random, whether it comes to rest and how still it lies; and the
// same ball with its map at 256 to 1024 texels a face on a plain plane (its own texel budget,
// clients/physics/plain_plane.hpp): how deep it rests and what a step costs rolling.
// Measures only; nothing asserted (tests/physics/test_ball_on_flat_ground.cpp and
// test_textured_objects_on_plain_plane.cpp hold the behaviour).
#include <BulletCollision/CollisionShapes/btSphereShape.h>

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
#include "clients/physics/plain_plane.hpp"
#include "clients/physics/textured_ball.hpp"
#include "tests/physics/mesh_rolling_scenes.hpp"
#include "tests/physics/textured_ball_scene.hpp"

namespace {

using namespace thx;
using namespace thx::phys;
using namespace thx::phys::test;
namespace tb = thx::phys::test::textured_ball;

constexpr const char* kHelp = R"(usage: bench_ball_own_texels [--starts N] [--texels N,N,...] [--json F] [--csv F] [--md F]

The tests' 1 cm, 30 g dimpled ball (dimples 3.9 mm apart, 0.25 mm deep, 256 texels a face of the
cube laid on it), no rolling friction, 1 ms steps:
  bowl    let down 0.2 mm over the bottom of the inside of a smooth UV sphere mesh (5 cm radius,
          128 segments, its bottom turned onto the equator), turned at random (std::mt19937,
          seeds 101 to 100 + N): with the rest detector, how many sleep within 3 s and within
          8 s; without it, over seconds 5-8, the fastest it moves (the largest and the median of
          the starts) and the mean wall-clock time of a step
  plane   the same dimples at N texels a face on a plain plane: the texels its cap holds by the
          raster's count (plainPlaneTexels) and the budget it is held to, how far into its radius
          it rests after 0.3 s, and the mean time of a step rolling at 0.1 m/s for 1 s, with its
          speed at the end (the dimples brake it; a smooth sphere keeps 0.1 m/s)
  --starts N      bowl starts (default 24)
  --texels LIST   plane: texels a face (default 256,384,512,768,1024)
  --json/--csv/--md F   results
)";

constexpr double kBowlRadius = 0.05;

struct BowlStart {
  double asleep_at_s = -1.0;  // with the rest detector; -1: awake after 8 s
  double fastest_late = 0.0;  // without it, seconds 5-8 (m/s)
  double us_per_step = 0.0;   // without it
};

BowlStart letDownInBowl(const tex::TextureMap& dimples, unsigned seed) {
  const mesh::GeneratedMesh bowl = mesh::sphere(kBowlRadius, 128, 64, mesh_rolling::kTileM);
  const FaceTexture texture = tb::ballTexture(dimples);
  BowlStart result;
  for (const bool rest : {true, false}) {
    WorldOptions options;
    options.rest.enabled = rest;
    PhysicsWorld world(options);
    MeshContactOptions smooth;
    smooth.smooth = true;
    Eigen::Isometry3d turned = Eigen::Isometry3d::Identity();
    turned.linear() = mesh_rolling::bottomOnTheEquator(kBowlRadius);
    world.addTexturedMesh(bowl.mesh, turned, {0.5, 0.0, 0.0}, smooth);
    Eigen::Isometry3d pose = at(0.0, 0.0, -kBowlRadius + tb::kRadius + 2e-4);
    pose.linear() = tb::anyTurn(100 + seed);
    btRigidBody& ball = world.addTexturedSphere(tb::kRadius, tb::kMass, pose, {0.5, 0.0, 0.0, 0.0}, texture);
    const int steps = 8000;
    const auto t0 = std::chrono::steady_clock::now();
    for (int k = 0; k < steps; ++k) {
      world.step(tb::kDt);
      if (rest && ball.getActivationState() == ISLAND_SLEEPING) {
        result.asleep_at_s = (k + 1) * tb::kDt;
        break;
      }
      if (!rest && k >= 4000) result.fastest_late = std::max(result.fastest_late, velocityOf(ball).norm());
    }
    if (!rest)
      result.us_per_step = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count() / steps;
  }
  return result;
}

struct PlaneRow {
  int texels = 0;
  double raster_count = 0.0, budget = 0.0;
  double rest_depth = 0.0;  // into its radius (m)
  double us_rolling = 0.0, speed_after = 0.0;
};

PlaneRow onPlainPlane(int texels) {
  const tex::TextureMap map = heightMap(texels, tb::kTile, tb::dimples);
  const FaceTexture texture = tb::ballTexture(map);
  PhysicsWorld world;
  world.addPlainPlane(at(0.0, 0.0, 0.0), {0.5, 0.0, 0.0});
  btRigidBody& ball =
      world.addTexturedSphere(tb::kRadius, tb::kMass, at(0.0, 0.0, tb::kRadius + 1e-4), {0.5, 0.0, 0.0, 0.0}, texture);
  PlaneRow row;
  row.texels = texels;
  row.raster_count = plainPlaneTexels(*ball.getCollisionShape());
  row.budget = plainPlaneTexelBudget(*ball.getCollisionShape());
  for (int k = 0; k < 300; ++k) world.step(tb::kDt);
  row.rest_depth = tb::kRadius - positionOf(ball).z();
  setRolling(ball, 0.1, tb::kRadius);
  const int steps = 1000;
  const auto t0 = std::chrono::steady_clock::now();
  for (int k = 0; k < steps; ++k) world.step(tb::kDt);
  row.us_rolling = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count() / steps;
  row.speed_after = velocityOf(ball).norm();
  return row;
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

int run(int argc, char** argv) {
  int starts = 24;
  std::vector<int> texels{256, 384, 512, 768, 1024};
  std::string json, csv, md;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (i + 1 >= argc) throw UsageError(a + " needs a value (see --help)");
    const std::string v = argv[++i];
    if (a == "--starts") starts = int(cli::parseInteger(a, v, 1, 1000));
    else if (a == "--texels") texels = cli::parseIntegerList(a, v, 16, 2048);
    else if (a == "--json") json = v;
    else if (a == "--csv") csv = v;
    else if (a == "--md") md = v;
    else throw UsageError("unknown option " + a + " (see --help)");
  }
  const tex::TextureMap dimples = tb::dimpleMap();
  std::vector<BowlStart> bowl;
  for (int s = 1; s <= starts; ++s) {
    std::fprintf(stderr, "\rbench_ball_own_texels: bowl, start %d of %d ...", s, starts);
    bowl.push_back(letDownInBowl(dimples, unsigned(s)));
  }
  std::fprintf(stderr, "\n");
  int asleep_3 = 0, asleep_8 = 0;
  double fastest = 0.0, us = 0.0;
  std::vector<double> late;
  for (const BowlStart& b : bowl) {
    asleep_3 += b.asleep_at_s >= 0.0 && b.asleep_at_s <= 3.0;
    asleep_8 += b.asleep_at_s >= 0.0;
    fastest = std::max(fastest, b.fastest_late);
    late.push_back(b.fastest_late);
    us += b.us_per_step / double(bowl.size());
  }
  std::vector<PlaneRow> plane;
  for (int n : texels) {
    std::fprintf(stderr, "bench_ball_own_texels: plain plane, %d texels a face ...\n", n);
    plane.push_back(onPlainPlane(n));
  }
  const std::string stamp = bench::fmt("%s, %s build, %s", bench::isoNow().c_str(), bench::buildType(),
                                       bench::machineSummary().c_str());
  if (!csv.empty()) {
    std::string c = "start,asleep_at_s,fastest_late_mm_s,us_per_step\n";
    for (std::size_t k = 0; k < bowl.size(); ++k)
      c += bench::fmt("%zu,%.3f,%.4f,%.1f\n", k + 1, bowl[k].asleep_at_s, bowl[k].fastest_late * 1e3, bowl[k].us_per_step);
    c += "\ntexels,raster_count,budget,rest_depth_um,us_per_step_rolling,speed_after_m_s\n";
    for (const PlaneRow& r : plane)
      c += bench::fmt("%d,%.0f,%.0f,%.2f,%.1f,%.4f\n", r.texels, r.raster_count, r.budget, r.rest_depth * 1e6,
                      r.us_rolling, r.speed_after);
    bench::writeTextFile(csv, c);
  }
  if (!json.empty()) {
    std::string j = bench::fmt("{\"stamp\": \"%s\", \"bowl\": {\"starts\": %d, \"asleep_within_3_s\": %d, "
                               "\"asleep_within_8_s\": %d, \"fastest_late_mm_s\": %.4f, \"median_late_mm_s\": %.4f, "
                               "\"us_per_step\": %.1f}, \"plane\": [",
                               stamp.c_str(), starts, asleep_3, asleep_8, fastest * 1e3, median(late) * 1e3, us);
    for (std::size_t k = 0; k < plane.size(); ++k) {
      const PlaneRow& r = plane[k];
      j += bench::fmt("%s{\"texels\": %d, \"raster_count\": %.0f, \"budget\": %.0f, \"rest_depth_um\": %.2f, "
                      "\"us_per_step_rolling\": %.1f, \"speed_after_m_s\": %.4f}",
                      k ? ", " : "", r.texels, r.raster_count, r.budget, r.rest_depth * 1e6, r.us_rolling, r.speed_after);
    }
    bench::writeTextFile(json, j + "]}\n");
  }
  if (!md.empty()) {
    std::string t = "Measured " + stamp + ".\n\n";
    t += bench::fmt("In the smooth bowl, %d starts: with the rest detector asleep within 3 s: **%d**, within 8 s: %d; "
                    "without it, fastest over seconds 5–8: %.3f mm/s at most, %.3f the median; a step %.0f µs.\n\n",
                    starts, asleep_3, asleep_8, fastest * 1e3, median(late) * 1e3, us);
    t += "| texels a face | by the raster's count | budget | rests into its radius | rolling: a step | speed after 1 s |\n"
         "|---:|---:|---:|---:|---:|---:|\n";
    for (const PlaneRow& r : plane)
      t += bench::fmt("| %d | %.0f | %.0f | %.1f µm | %.0f µs | %.4f m/s |\n", r.texels, r.raster_count, r.budget,
                      r.rest_depth * 1e6, r.us_rolling, r.speed_after);
    bench::writeTextFile(md, t);
  }
  std::printf("bowl: %d starts, asleep within 3 s %d, within 8 s %d; awake, fastest in seconds 5-8 %.3f mm/s (median "
              "%.3f); %.0f us per step\n",
              starts, asleep_3, asleep_8, fastest * 1e3, median(late) * 1e3, us);
  for (const PlaneRow& r : plane)
    std::printf("plain plane, %4d texels a face: %.0f texels (budget %.0f), rests %.1f um in, %.0f us per step rolling, "
                "%.4f m/s after 1 s\n",
                r.texels, r.raster_count, r.budget, r.rest_depth * 1e6, r.us_rolling, r.speed_after);
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return bench::benchMain(argc, argv, kHelp, "bench_ball_own_texels", run); }
