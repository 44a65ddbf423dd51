// A ball on meshes smaller than itself (issue 29; docs/physics.md "Across a crease", "Small
// triangles"): a 1 cm ball, plain or recessed 0.5 mm by its bump map, pressed by its weight on a
// smooth UV sphere mesh of 20 mm down to 0.25 mm, or across a 1 mm rod mesh, along several lines.
// Where it rests against where it touches, and what a step costs where the whole mesh lies within
// the ball's reach. Measures only; nothing asserted (tests/physics/test_textured_ball_on_mesh.cpp,
// test_small_triangle_sphere.cpp and test_smooth_foot.cpp hold the behaviour).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "benchmarks/bench_help.hpp"
#include "benchmarks/bench_rig.hpp"
#include "benchmarks/bench_stamp.hpp"
#include "meshes/mesh_generators.hpp"
#include "tests/physics/textured_ball_on_mesh_scene.hpp"

namespace {

using namespace thx;
using namespace thx::phys;
using namespace thx::phys::test;
namespace ball = thx::phys::test::textured_ball;

constexpr const char* kHelp = R"(usage: bench_ball_on_small_mesh [--json F] [--csv F] [--md F]

A 1 cm, 30 g ball, plain or recessed 0.5 mm everywhere by its bump map (it touches on its
9.5 mm radius), pressed by its weight (gravity off, the ball kept from turning) for 0.6 s at 1 ms
steps onto a fixed smooth mesh at the origin:
  - UV spheres (128 segments, 64 rings) of radius 20, 5, 1, 0.5 and 0.25 mm, along five lines
    through their centre, on the world's axes and off them;
  - a rod: a cylinder mesh of 1 mm radius, 10 cm long (128 segments, 64 rows), from five
    directions round its axis.
For each mesh and ball: how far from where it touches the ball ends (its centre's distance from
the mesh's centre or axis against the radii's sum; negative: into it) and how far off its line it
strayed, the worst over the lines, and the time per step (the fastest and slowest line; the
machine is shared: compare within a run). A triangle of the 0.25 mm sphere is some 1e-4 mm²,
every one of them within the ball's reach.

  --json/--csv/--md F   results
)";

constexpr int kSteps = 600;
constexpr double kRecessM = 0.5e-3;
constexpr double kRodRadius = 1e-3;
const double kSphereRadii[] = {0.02, 0.005, 0.001, 0.0005, 0.00025};
const double kRodAngles[] = {0.0, 0.3, 0.7, 1.1, 2.0};

struct Row {
  std::string mesh;
  bool recessed = false;
  double worst_off_touch_m = 0.0;  // signed, the largest in size
  double worst_off_line_m = 0.0;
  double fastest_us = 1e30, slowest_us = 0.0;
};

// One press: the world holds the mesh; `touch` is where the centre rests if the ball touches.
void press(PhysicsWorld& world, const Eigen::Vector3d& u, double touch, bool recessed, const FaceTexture& texture,
           Row& row, bool radial_in_plane) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = (touch + 1e-4) * u;
  btRigidBody& b = recessed ? world.addTexturedSphere(ball::kRadius, ball::kMass, pose, {0.5, 0.0, 0.0}, texture)
                            : world.addSphere(ball::kRadius, ball::kMass, pose, {0.5, 0.0, 0.0});
  const auto t0 = std::chrono::steady_clock::now();
  const ball::PressedRest rest = ball::pressTowardsOrigin(world, b, u, kSteps);
  const double us = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count() / kSteps;
  // On the rod the distance that matters is from its axis (z is along it).
  const Eigen::Vector3d c = positionOf(b);
  const double distance = radial_in_plane ? c.head<2>().norm() : rest.distance_m;
  const double off = distance - touch;
  if (std::fabs(off) > std::fabs(row.worst_off_touch_m)) row.worst_off_touch_m = off;
  row.worst_off_line_m = std::max(row.worst_off_line_m, rest.off_line_m);
  row.fastest_us = std::min(row.fastest_us, us);
  row.slowest_us = std::max(row.slowest_us, us);
}

int run(int argc, char** argv) {
  const bench::ResultFiles files = bench::resultFilesOnly(argc, argv);
  const std::string &json = files.json, &csv = files.csv, &md = files.md;
  const tex::TextureMap recess_map = ball::uniformRecess(kRecessM);
  const FaceTexture recessed_texture = ball::ballTexture(recess_map);
  std::vector<Row> rows;
  for (const double radius : kSphereRadii) {
    for (const bool recessed : {false, true}) {
      Row row;
      row.mesh = bench::fmt("sphere %g mm", radius * 1e3);
      row.recessed = recessed;
      std::fprintf(stderr, "bench_ball_on_small_mesh: %s ball on the %s ...\n", recessed ? "recessed" : "plain", row.mesh.c_str());
      const double touch = radius + ball::kRadius - (recessed ? kRecessM : 0.0);
      for (const Eigen::Vector3d& line : ball::kPressLines) {
        mesh_rolling::SphereScene scene(128, true, radius);
        press(scene.world, line.normalized(), touch, recessed, recessed_texture, row, false);
      }
      rows.push_back(row);
    }
  }
  const mesh::GeneratedMesh rod = mesh::cylinder(kRodRadius, 0.1, 128, 64, 0.02);
  for (const bool recessed : {false, true}) {
    Row row;
    row.mesh = bench::fmt("rod %g mm", kRodRadius * 1e3);
    row.recessed = recessed;
    std::fprintf(stderr, "bench_ball_on_small_mesh: %s ball on the %s ...\n", recessed ? "recessed" : "plain", row.mesh.c_str());
    const double touch = kRodRadius + ball::kRadius - (recessed ? kRecessM : 0.0);
    for (const double angle : kRodAngles) {
      PhysicsWorld world;
      Eigen::Isometry3d rod_pose = Eigen::Isometry3d::Identity();
      rod_pose.translation() = Eigen::Vector3d(0, 0, -0.05);  // the cylinder's axis along z, centred on the origin
      world.addTexturedMesh(rod.mesh, rod_pose, {1.0, 0.0, 0.0}, MeshContactOptions{});
      press(world, Eigen::Vector3d(std::cos(angle), std::sin(angle), 0.0), touch, recessed, recessed_texture, row, true);
    }
    rows.push_back(row);
  }

  const std::string stamp = bench::fmt("%s, %s build, %s", bench::isoNow().c_str(), bench::buildType(),
                                       bench::machineSummary().c_str());
  auto kind = [](const Row& r) { return r.recessed ? "recessed 0.5 mm" : "plain"; };
  if (!csv.empty()) {
    std::string c = "mesh,ball,worst_off_touch_um,worst_off_line_um,fastest_us_per_step,slowest_us_per_step\n";
    for (const Row& r : rows)
      c += bench::fmt("%s,%s,%.4f,%.4f,%.1f,%.1f\n", r.mesh.c_str(), kind(r), r.worst_off_touch_m * 1e6,
                      r.worst_off_line_m * 1e6, r.fastest_us, r.slowest_us);
    bench::writeTextFile(csv, c);
  }
  if (!json.empty()) {
    std::string j = bench::fmt("{\"stamp\": \"%s\", \"steps\": %d, \"rows\": [", stamp.c_str(), kSteps);
    for (std::size_t k = 0; k < rows.size(); ++k) {
      const Row& r = rows[k];
      j += bench::fmt("%s{\"mesh\": \"%s\", \"ball\": \"%s\", \"worst_off_touch_um\": %.5f, \"worst_off_line_um\": %.5f, "
                      "\"fastest_us_per_step\": %.2f, \"slowest_us_per_step\": %.2f}",
                      k ? ", " : "", r.mesh.c_str(), kind(r), r.worst_off_touch_m * 1e6, r.worst_off_line_m * 1e6,
                      r.fastest_us, r.slowest_us);
    }
    bench::writeTextFile(json, j + "]}\n");
  }
  if (!md.empty()) {
    std::string t = "Measured " + stamp +
                    ". A 1 cm ball pressed by its weight for 0.6 s onto a smooth mesh along five lines: where it "
                    "rests against where it touches (negative: into it) and how far off its line it strayed, the "
                    "worst of the five; the time per step, the fastest and the slowest line.\n\n"
                    "| mesh | ball | off the touch | off the line | step |\n"
                    "|---|---|---:|---:|---:|\n";
    for (const Row& r : rows)
      t += bench::fmt("| %s | %s | %+.2f µm | %.2f µm | %.0f–%.0f µs |\n", r.mesh.c_str(), kind(r),
                      r.worst_off_touch_m * 1e6, r.worst_off_line_m * 1e6, r.fastest_us, r.slowest_us);
    bench::writeTextFile(md, t);
  }
  for (const Row& r : rows)
    std::printf("%s ball on the %s: %+.2f um off the touch, %.2f um off the line at worst, %.0f-%.0f us/step\n", kind(r),
                r.mesh.c_str(), r.worst_off_touch_m * 1e6, r.worst_off_line_m * 1e6, r.fastest_us, r.slowest_us);
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return bench::benchMain(argc, argv, kHelp, "bench_ball_on_small_mesh", run); }
