// A ball with a bump map on ground with no features of its own, met on the ball's own texels
// (issue 29; clients/physics/ball_on_flat_ground.hpp; docs/physics.md "A ball with a bump map on
// flat ground"): the shipped dimpled ball let down at the bottom of a smooth bowl (a mesh's bent
// chart) from starts turned at random, whether it comes to rest and how still it lies; the same
// in a smooth relief dish (a relief plane's paraboloid, met on the ball's own texels since its
// depth bends by less than kSmoothReliefBend a texel); and the
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

constexpr const char* kHelp = R"(usage: bench_ball_own_texels [--starts N] [--dish-starts N] [--texels N,N,...] [--json F] [--csv F] [--md F]

The tests' 1 cm, 30 g dimpled ball (dimples 3.9 mm apart, 0.25 mm deep, 256 texels a face of the
cube laid on it), no rolling friction, 1 ms steps:
  bowl    let down 0.2 mm over the bottom of the inside of a smooth UV sphere mesh (5 cm radius,
          128 segments, its bottom turned onto the equator), turned at random (std::mt19937,
          seeds 101 to 100 + N): with the rest detector, how many sleep within 3 s and within
          8 s; without it, over seconds 5-8, the fastest it moves (the largest and the median of
          the starts) and the mean wall-clock time of a step
  dish    let down 0.2 mm over a relief plane's paraboloid dish (curvature 10 /m, 256 texels over
          4 cm) within 1 mm of its centre (std::mt19937 seeded 1000 + n, turned by the bowl's
          turn n): with the rest detector, how many sleep within 8 s; without it, over the eighth
          second, how many rock in place (faster than 0.5 mm/s, the centre within 50 um), how
          many swing (the centre farther: rolling on the land between the dimples, as a ball
          without rolling friction may), how fast the others move at most, and the mean
          wall-clock time of a step
  plane   the same dimples at N texels a face on a plain plane: the texels its cap holds by the
          raster's count (plainPlaneTexels) and the budget it is held to, how far into its radius
          it rests after 0.3 s, and the mean time of a step rolling at 0.1 m/s for 1 s, with its
          speed at the end (the dimples brake it; a smooth sphere keeps 0.1 m/s)
  --starts N      bowl starts (default 24)
  --dish-starts N dish starts (default 24)
  --texels LIST   plane: texels a face (default 256,384,512,768,1024)
  --json/--csv/--md F   results
)";

constexpr double kBowlRadius = 0.05;

// The dimpled ball let down where `addGround` puts its ground, at `pose`, 8 s twice: with the rest
// detector, when it sleeps (-1: awake after 8 s); without it, the fastest it moves over seconds
// 5-8 and over the eighth, how far its centre strays over the eighth and the mean wall-clock time
// of a step.
struct LetDown {
  double asleep_at_s = -1.0;
  double fastest_late = 0.0;  // m/s
  double fastest_last = 0.0;  // m/s
  double strayed = 0.0;       // m
  double us_per_step = 0.0;
};
template <class AddGround>
LetDown letDown(const AddGround& addGround, const FaceTexture& texture, const Eigen::Isometry3d& pose) {
  LetDown result;
  for (const bool rest : {true, false}) {
    WorldOptions options;
    options.rest.enabled = rest;
    PhysicsWorld world(options);
    addGround(world);
    btRigidBody& ball = world.addTexturedSphere(tb::kRadius, tb::kMass, pose, {0.5, 0.0, 0.0, 0.0}, texture);
    const int steps = 8000;
    Eigen::Vector3d settled = Eigen::Vector3d::Zero();
    const auto t0 = std::chrono::steady_clock::now();
    for (int k = 0; k < steps; ++k) {
      world.step(tb::kDt);
      if (rest && ball.getActivationState() == ISLAND_SLEEPING) {
        result.asleep_at_s = (k + 1) * tb::kDt;
        break;
      }
      if (rest) continue;
      if (k >= 4000) result.fastest_late = std::max(result.fastest_late, velocityOf(ball).norm());
      if (k == steps - 1001) settled = positionOf(ball);
      if (k >= steps - 1000) {
        result.strayed = std::max(result.strayed, (positionOf(ball) - settled).norm());
        result.fastest_last = std::max(result.fastest_last, velocityOf(ball).norm());
      }
    }
    if (!rest)
      result.us_per_step = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count() / steps;
  }
  return result;
}

LetDown letDownInBowl(const mesh::GeneratedMesh& bowl, const FaceTexture& texture, unsigned seed) {
  Eigen::Isometry3d pose = at(0.0, 0.0, -kBowlRadius + tb::kRadius + 2e-4);
  pose.linear() = tb::anyTurn(100 + seed);
  return letDown(
      [&](PhysicsWorld& world) {
        MeshContactOptions smooth;
        smooth.smooth = true;
        Eigen::Isometry3d turned = Eigen::Isometry3d::Identity();
        turned.linear() = mesh_rolling::bottomOnTheEquator(kBowlRadius);
        world.addTexturedMesh(bowl.mesh, turned, {0.5, 0.0, 0.0}, smooth);
      },
      texture, pose);
}

// Over the eighth second: rocking in place (faster than this, the centre within the stray) against
// swinging (the centre farther) and lying still. A ball still settling late in the sixth second is
// neither: measured over seconds 5-8, one such start on the grooves read as rocking.
constexpr double kSwingStray = 50e-6, kRockingSpeed = 0.5e-3;

LetDown letDownInDish(const tex::TexturedSurface& dish, const FaceTexture& texture, unsigned seed) {
  const Eigen::Vector2d start = tb::dishStart(seed);
  Eigen::Isometry3d pose = at(start.x(), start.y(), tb::dishHeight(start.x(), start.y()) + tb::kRadius + 2e-4);
  pose.linear() = tb::anyTurn(100 + seed);
  return letDown([&](PhysicsWorld& world) { world.addReliefPlane(dish, {0.5, 0.0, 0.0}); }, texture, pose);
}

struct DishSummary {
  int starts = 0, asleep = 0, rocking = 0, swinging = 0;
  double fastest_rocking = 0.0, fastest_still = 0.0, us = 0.0;
};
DishSummary summarise(const std::vector<LetDown>& dish) {
  DishSummary d;
  d.starts = int(dish.size());
  for (const LetDown& s : dish) {
    d.asleep += s.asleep_at_s >= 0.0;
    d.us += s.us_per_step / double(dish.size());
    if (s.strayed > kSwingStray) {
      ++d.swinging;
    } else if (s.fastest_last > kRockingSpeed) {
      ++d.rocking;
      d.fastest_rocking = std::max(d.fastest_rocking, s.fastest_last);
    } else {
      d.fastest_still = std::max(d.fastest_still, s.fastest_last);
    }
  }
  return d;
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
  int starts = 24, dish_starts = 24;
  std::vector<int> texels{256, 384, 512, 768, 1024};
  std::string json, csv, md;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (i + 1 >= argc) throw UsageError(a + " needs a value (see --help)");
    const std::string v = argv[++i];
    if (a == "--starts") starts = int(cli::parseInteger(a, v, 1, 1000));
    else if (a == "--dish-starts") dish_starts = int(cli::parseInteger(a, v, 1, 1000));
    else if (a == "--texels") texels = cli::parseIntegerList(a, v, 16, 2048);
    else if (a == "--json") json = v;
    else if (a == "--csv") csv = v;
    else if (a == "--md") md = v;
    else throw UsageError("unknown option " + a + " (see --help)");
  }
  const tex::TextureMap dimples = tb::dimpleMap();
  const FaceTexture dimpled = tb::ballTexture(dimples);
  const mesh::GeneratedMesh bowl_mesh = mesh::sphere(kBowlRadius, 128, 64, mesh_rolling::kTileM);
  std::vector<LetDown> bowl;
  for (int s = 1; s <= starts; ++s) {
    std::fprintf(stderr, "\rbench_ball_own_texels: bowl, start %d of %d ...", s, starts);
    bowl.push_back(letDownInBowl(bowl_mesh, dimpled, unsigned(s)));
  }
  std::fprintf(stderr, "\n");
  int asleep_3 = 0, asleep_8 = 0;
  double fastest = 0.0, us = 0.0;
  std::vector<double> late;
  for (const LetDown& b : bowl) {
    asleep_3 += b.asleep_at_s >= 0.0 && b.asleep_at_s <= 3.0;
    asleep_8 += b.asleep_at_s >= 0.0;
    fastest = std::max(fastest, b.fastest_late);
    late.push_back(b.fastest_late);
    us += b.us_per_step / double(bowl.size());
  }
  const SurfaceHolder dish_plane = holdSurface(tb::dishMap(), tb::kDishExtent, true);
  std::vector<LetDown> dish;
  for (int s = 1; s <= dish_starts; ++s) {
    std::fprintf(stderr, "\rbench_ball_own_texels: dish, start %d of %d ...", s, dish_starts);
    dish.push_back(letDownInDish(dish_plane.surface, dimpled, unsigned(s)));
  }
  std::fprintf(stderr, "\n");
  const DishSummary d = summarise(dish);
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
    c += "\ndish_start,asleep_at_s,fastest_late_mm_s,fastest_last_mm_s,strayed_um,us_per_step\n";
    for (std::size_t k = 0; k < dish.size(); ++k)
      c += bench::fmt("%zu,%.3f,%.4f,%.4f,%.2f,%.1f\n", k + 1, dish[k].asleep_at_s, dish[k].fastest_late * 1e3,
                      dish[k].fastest_last * 1e3, dish[k].strayed * 1e6, dish[k].us_per_step);
    c += "\ntexels,raster_count,budget,rest_depth_um,us_per_step_rolling,speed_after_m_s\n";
    for (const PlaneRow& r : plane)
      c += bench::fmt("%d,%.0f,%.0f,%.2f,%.1f,%.4f\n", r.texels, r.raster_count, r.budget, r.rest_depth * 1e6,
                      r.us_rolling, r.speed_after);
    bench::writeTextFile(csv, c);
  }
  if (!json.empty()) {
    std::string j = bench::fmt("{\"stamp\": \"%s\", \"bowl\": {\"starts\": %d, \"asleep_within_3_s\": %d, "
                               "\"asleep_within_8_s\": %d, \"fastest_late_mm_s\": %.4f, \"median_late_mm_s\": %.4f, "
                               "\"us_per_step\": %.1f}, ",
                               stamp.c_str(), starts, asleep_3, asleep_8, fastest * 1e3, median(late) * 1e3, us);
    j += bench::fmt("\"dish\": {\"starts\": %d, \"asleep_within_8_s\": %d, \"rocking\": %d, \"swinging\": %d, "
                    "\"fastest_rocking_mm_s\": %.4f, \"fastest_still_mm_s\": %.4f, \"us_per_step\": %.1f}, \"plane\": [",
                    d.starts, d.asleep, d.rocking, d.swinging, d.fastest_rocking * 1e3, d.fastest_still * 1e3, d.us);
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
    t += bench::fmt("In the relief dish, %d starts: with the rest detector asleep within 8 s: **%d**; without it, over "
                    "the eighth second, rocking in place: **%d**%s, swinging on the land: %d, the others at up to %.3f mm/s; "
                    "a step %.0f µs.\n\n",
                    d.starts, d.asleep, d.rocking,
                    d.rocking ? bench::fmt(" (up to %.2f mm/s)", d.fastest_rocking * 1e3).c_str() : "", d.swinging,
                    d.fastest_still * 1e3, d.us);
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
  std::printf("dish: %d starts, asleep within 8 s %d; awake, rocking in place %d (up to %.3f mm/s), swinging %d, the "
              "others up to %.3f mm/s; %.0f us per step\n",
              d.starts, d.asleep, d.rocking, d.fastest_rocking * 1e3, d.swinging, d.fastest_still * 1e3, d.us);
  for (const PlaneRow& r : plane)
    std::printf("plain plane, %4d texels a face: %.0f texels (budget %.0f), rests %.1f um in, %.0f us per step rolling, "
                "%.4f m/s after 1 s\n",
                r.texels, r.raster_count, r.budget, r.rest_depth * 1e6, r.us_rolling, r.speed_after);
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return bench::benchMain(argc, argv, kHelp, "bench_ball_own_texels", run); }
