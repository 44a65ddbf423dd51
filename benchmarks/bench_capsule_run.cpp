// A capsule against a textured box (issue 29; clients/physics/capsule_balls.hpp,
// ball_on_object_faces.hpp): how well the search along a capsule's run over a face finds the ball
// whose lifted gap is least, against the spacing it samples at, and what it costs. Measures only;
// nothing asserted (tests/physics/test_capsule_on_box_faces.cpp holds the behaviour).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "base/cli_number.hpp"
#include "base/error.hpp"
#include "benchmarks/bench_help.hpp"
#include "benchmarks/bench_rig.hpp"
#include "benchmarks/bench_stamp.hpp"
#include "clients/physics/ball_on_object_faces.hpp"
#include "clients/physics/capsule_balls.hpp"
#include "tests/physics/grooved_block_scene.hpp"

namespace {

using namespace thx;
using namespace thx::phys;
using namespace thx::phys::test;
using namespace thx::phys::test::grooved_block;

constexpr const char* kHelp = R"(usage: bench_capsule_run [--poses N] [--json F] [--csv F] [--md F]

A capsule lying on the top face of a 2 x 2 x 1 cm box whose faces carry a relief at 128 texels
over 4 cm (0.31 mm texels): V-grooves 4 mm apart and 1 mm deep, or sine bumps 3 mm apart and
0.3 mm high. N poses (default 200, a fixed seed): the capsule 2 cm between its caps' centres, of
radius 2 or 4 mm, turned at random about the face's normal, its middle anywhere on the face, its
axis level or tilted up to 3 degrees, 0.1 mm over the face. For each, the search of
capsule_balls.hpp (leastOnHalves: the run over each of the face's two triangles sampled every
`spacing` texels, the least sample of each half refined by three parabolas) against the least
lifted gap along the run found by brute force (every micrometre): its error (what it found less
the least; never negative), its mean and largest over the poses, and the time of a search of
both triangles, at spacings of 0.5, 1 (the product's), 2 and 4 texels.

  --poses N       poses per relief and radius (default 200)
  --json/--csv/--md F   results
)";

struct Row {
  std::string relief;
  double radius_m = 0, spacing_texels = 0;
  double mean_error_m = 0, max_error_m = 0, us_per_search = 0, gaps_per_search = 0;
};

double bumps(double x, double y) {
  constexpr double kBumpPeriod = 0.003, kBumpHeight = 0.0003;
  return 0.5 * kBumpHeight * (std::sin(2 * kPi * x / kBumpPeriod) * std::sin(2 * kPi * y / kBumpPeriod) - 1.0);
}

struct Pose {
  Eigen::Vector3d a, b;
};

std::vector<Pose> posesOf(int count, double radius, const Eigen::Vector3d& half) {
  std::mt19937 rng(29);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Pose> poses;
  for (int k = 0; k < count; ++k) {
    const double turn = 2 * kPi * unit(rng), tilt = (unit(rng) - 0.5) * 2 * 3.0 * kPi / 180.0;
    const Eigen::Vector3d axis(std::cos(turn) * std::cos(tilt), std::sin(turn) * std::cos(tilt), std::sin(tilt));
    const Eigen::Vector3d middle((unit(rng) - 0.5) * 2 * half.x(), (unit(rng) - 0.5) * 2 * half.y(), half.z() + radius + 1e-4);
    poses.push_back({middle - 0.01 * axis, middle + 0.01 * axis});
  }
  return poses;
}

int run(int argc, char** argv) {
  int pose_count = 200;
  std::string json, csv, md;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (i + 1 >= argc) throw UsageError(a + " needs a value (see --help)");
    const std::string v = argv[++i];
    if (a == "--poses") pose_count = int(cli::parseInteger(a, v, 1, 100000));
    else if (a == "--json") json = v;
    else if (a == "--csv") csv = v;
    else if (a == "--md") md = v;
    else throw UsageError("unknown option " + a + " (see --help)");
  }
  const Eigen::Vector3d half(0.01, 0.01, 0.005);
  std::vector<Row> rows;
  for (const std::string relief : {"V-grooves", "sine bumps"}) {
    const tex::TextureMap map = heightMap(128, kExtent, relief == "V-grooves" ? vGrooves : bumps);
    FaceTexture texture;
    texture.map = &map;
    texture.tile_m = kExtent;
    const std::unique_ptr<ObjectFaces> box_faces = boxFaces(half, texture);
    const ObjectFaces& faces = *box_faces;
    std::vector<std::uint32_t> top;
    for (std::uint32_t t = 0; t < std::uint32_t(faces.mesh.triangles.size()); ++t)
      if (mesh::faceNormal(faces.mesh, t).z() > 0.5) top.push_back(t);
    for (const double radius : {0.002, 0.004}) {
      const std::vector<Pose> poses = posesOf(pose_count, radius, half);
      // The least lifted gap over each pose's runs, every micrometre.
      std::vector<double> least(poses.size(), 1e30);
      for (std::size_t p = 0; p < poses.size(); ++p)
        for (const std::uint32_t t : top) {
          const mesh::Triangle& c = faces.mesh.triangles[t];
          const SegmentOverTriangle over = segmentOverTriangle(faces.mesh.positions[c[0]], faces.mesh.positions[c[1]],
                                                               faces.mesh.positions[c[2]], poses[p].a, poses[p].b);
          if (!over.runs_over) continue;
          const double length = (poses[p].b - poses[p].a).norm() * (over.hi - over.lo);
          const int samples = std::max(1, int(std::ceil(length / 1e-6)));
          for (int k = 0; k <= samples; ++k) {
            const double along = over.lo + (over.hi - over.lo) * k / samples;
            least[p] = std::min(least[p], ballLiftedGap(faces.contact, poses[p].a + along * (poses[p].b - poses[p].a), t,
                                                        radius, faces.options));
          }
        }
      for (const double spacing : {0.5, 1.0, 2.0, 4.0}) {
        std::fprintf(stderr, "bench_capsule_run: %s, r %.0f mm, %.1f texels ...\n", relief.c_str(), radius * 1e3, spacing);
        Row row;
        row.relief = relief;
        row.radius_m = radius;
        row.spacing_texels = spacing;
        std::vector<double> found(poses.size(), 1e30);
        long gaps = 0;
        const auto t0 = std::chrono::steady_clock::now();
        for (std::size_t p = 0; p < poses.size(); ++p) {
          const Eigen::Vector3d a = poses[p].a, b = poses[p].b;
          for (const std::uint32_t t : top) {
            const mesh::Triangle& c = faces.mesh.triangles[t];
            const SegmentOverTriangle over = segmentOverTriangle(faces.mesh.positions[c[0]], faces.mesh.positions[c[1]],
                                                                 faces.mesh.positions[c[2]], a, b);
            if (!over.runs_over) continue;
            const auto gap = [&](double along) {
              ++gaps;
              return ballLiftedGap(faces.contact, a + along * (b - a), t, radius, faces.options);
            };
            const RunBalls balls = leastOnHalves(over.lo, over.hi, spacing * faces.texel_m / (b - a).norm(), 1e-9, gap);
            for (int k = 0; k < balls.count; ++k)
              found[p] = std::min(found[p], ballLiftedGap(faces.contact, a + balls.t[std::size_t(k)] * (b - a), t, radius,
                                                          faces.options));
          }
        }
        const auto t1 = std::chrono::steady_clock::now();
        row.us_per_search = std::chrono::duration<double, std::micro>(t1 - t0).count() / double(poses.size());
        row.gaps_per_search = double(gaps) / double(poses.size());
        for (std::size_t p = 0; p < poses.size(); ++p) {
          const double error = std::max(0.0, found[p] - least[p]);
          row.mean_error_m += error / double(poses.size());
          row.max_error_m = std::max(row.max_error_m, error);
        }
        rows.push_back(row);
      }
    }
  }
  const std::string stamp = bench::fmt("%s, %s build, %s", bench::isoNow().c_str(), bench::buildType(),
                                       bench::machineSummary().c_str());
  if (!csv.empty()) {
    std::string c = "relief,radius_mm,spacing_texels,mean_error_um,max_error_um,us_per_search,gaps_per_search\n";
    for (const Row& r : rows)
      c += bench::fmt("%s,%.1f,%.1f,%.4f,%.4f,%.2f,%.1f\n", r.relief.c_str(), r.radius_m * 1e3, r.spacing_texels,
                      r.mean_error_m * 1e6, r.max_error_m * 1e6, r.us_per_search, r.gaps_per_search);
    bench::writeTextFile(csv, c);
  }
  if (!json.empty()) {
    std::string j = bench::fmt("{\"stamp\": \"%s\", \"poses\": %d, \"rows\": [", stamp.c_str(), pose_count);
    for (std::size_t k = 0; k < rows.size(); ++k) {
      const Row& r = rows[k];
      j += bench::fmt("%s{\"relief\": \"%s\", \"radius_mm\": %.1f, \"spacing_texels\": %.1f, \"mean_error_um\": %.5f, "
                      "\"max_error_um\": %.5f, \"us_per_search\": %.3f, \"gaps_per_search\": %.2f}",
                      k ? ", " : "", r.relief.c_str(), r.radius_m * 1e3, r.spacing_texels, r.mean_error_m * 1e6,
                      r.max_error_m * 1e6, r.us_per_search, r.gaps_per_search);
    }
    bench::writeTextFile(json, j + "]}\n");
  }
  if (!md.empty()) {
    std::string t = "Measured " + stamp +
                    bench::fmt(". %d poses of a capsule (2 cm between its caps' centres) lying on a textured box's top face "
                               "at 0.31 mm texels; the search along its run over the face's two triangles against the least "
                               "lifted gap found every micrometre: its error (never negative) and the time of one search of "
                               "both triangles, with the lifted gaps it read.\n\n",
                               pose_count) +
                    "| relief | radius | spacing | mean error | largest error | µs per search | gaps read |\n"
                    "|---|---:|---:|---:|---:|---:|---:|\n";
    for (const Row& r : rows)
      t += bench::fmt("| %s | %.0f mm | %.1f texels | %.3f µm | %.3f µm | %.1f | %.0f |\n", r.relief.c_str(),
                      r.radius_m * 1e3, r.spacing_texels, r.mean_error_m * 1e6, r.max_error_m * 1e6, r.us_per_search,
                      r.gaps_per_search);
    bench::writeTextFile(md, t);
  }
  for (const Row& r : rows)
    std::printf("%-10s r %.0f mm, every %.1f texels: error mean %.3f um, largest %.3f um; %.1f us, %.0f gaps a search\n",
                r.relief.c_str(), r.radius_m * 1e3, r.spacing_texels, r.mean_error_m * 1e6, r.max_error_m * 1e6,
                r.us_per_search, r.gaps_per_search);
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return bench::benchMain(argc, argv, kHelp, "bench_capsule_run", run); }
