// A block set down around the squeezed pole of a normal-mapped bowl (issue 29; docs/physics.md,
// "Mesh scenes in physics-client"): the bowl of bricks (tests/support/bowl_scene.hpp) as a normal
// map, whose lathe uv squeezes the texture towards its floor's centre, with a wooden block set
// down at places around it, read three ways: the normal map at one point of each contact (what
// physics-client did before 2026-12-03), the relief the map's normals integrate to (what it does
// now: MeshGround), and the bricks' own relief map; then the bricks' normals leaning, read at one
// point and as their relief with the contacts leaning by the mean slope (MeshGround's reading of
// a leaning map). Whether the block comes to rest, and how fast it still moves.
// Measures only; nothing asserted (tests/physics_client/test_mesh_normal_map_relief.cpp holds the
// behaviour at two places).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "base/cli_number.hpp"
#include "base/error.hpp"
#include "benchmarks/bench_help.hpp"
#include "benchmarks/bench_rig.hpp"
#include "benchmarks/bench_stamp.hpp"
#include "clients/physics/bullet_convert.hpp"
#include "clients/physics/physics_world.hpp"
#include "clients/physics_client/physics_scene.hpp"
#include "scenes/scene_frames.hpp"
#include "scenes/scene_loader.hpp"
#include "tests/support/bowl_scene.hpp"
#include "textures/height_from_normals.hpp"

namespace {

using namespace thx;

constexpr const char* kHelp = R"(usage: bench_block_by_pole [--segments N] [--seconds T] [--json F] [--csv F] [--md F]

The bowl of bricks (scenes/brick_bowl.yaml's shape: half an ellipsoid 55.2 mm across and 43.2 mm
deep, bricks of 128 texels a 4 cm tile) with N segments, its floor's centre the pole of the
lathe's uv, which squeezes the texture there. A 10 x 10 x 6 mm, 5 g wooden block set down 0.5 mm
above the floor at 21 places within 17 mm of the pole: r = 0, 2, 4, 7, 10, 13 and 16 mm from a
point 0.76 mm off it, each turned three ways about the vertical, at 1 ms steps for T seconds, with the bricks read three ways: as a
normal map at one point of each contact (on the smooth chart), as the relief the normal map's
normals integrate to (physics-client's MeshGround for a map level on average), and as the bricks'
own relief map; then the bricks' normals leaning by a slope of 0.02 along v (outwards across the
floor), read at one point and as MeshGround reads such a map since 2026-12-03 (their relief, the
contacts' normals leaning by the mean slope). Per place and reading: the block's peak speed over the last second and how far
it moved in it; at rest is under 0.1 mm/s.

  --segments N   the bowl's tessellation (default 128)
  --seconds T    each run's length (default 3)
  --json/--csv/--md F   results
)";

struct Place {
  double r_mm = 0, turn_rad = 0;
  Eigen::Vector2d at = Eigen::Vector2d::Zero();  // m, from the floor's centre
};

struct Reading {
  const char* name;
  const char* representation;  // of the scene
  bool one_point;              // the normal map itself instead of MeshGround's texture
  double lean = 0.0;           // added to the normal map's slope along v (MeshGround's reading of such a map)
};
// The lean of the leaning rows: along v, the lathe's profile (outwards on the floor), not squeezed
// at the pole; 1.1 degrees, far below the block's friction.
constexpr double kLean = 0.02;
constexpr Reading kReadings[] = {{"normal map at one point", "normal", true},
                                 {"normal map as its integrated relief", "normal", false},
                                 {"relief map", "relief", false},
                                 {"leaning normal map at one point", "normal", true, kLean},
                                 {"leaning normal map as its relief, leaning", "normal", false, kLean}};

// `map`'s normals with `lean` added to their slope along v (texture y): n ~ (-h_x, -h_y, 1).
tex::TextureMap leaned(const tex::TextureMap& map, double lean) {
  tex::TextureMap out(map.width(), map.height(), tex::Representation::Normal);
  for (int j = 0; j < map.height(); ++j)
    for (int i = 0; i < map.width(); ++i) {
      const Eigen::Vector3f n = map.normal(i, j);
      out.setNormal(i, j, Eigen::Vector3f(n.x(), n.y() - float(lean) * n.z(), n.z()).normalized());
    }
  out.meta() = map.meta();
  return out;
}

struct Cell {
  double peak_mm_s = 0, moved_um = 0;
  bool atRest() const { return peak_mm_s < 0.1; }
};

std::vector<Place> places() {
  std::vector<Place> out;
  for (double r : {0.0, 2.0, 4.0, 7.0, 10.0, 13.0, 16.0})
    for (double turn : {0.3, 1.9, 3.6}) out.push_back({r, turn, Eigen::Vector2d(0.0007 + 1e-3 * r * std::cos(turn), 0.0003 + 1e-3 * r * std::sin(turn))});
  return out;
}

Cell settle(const Reading& reading, const Place& place, int segments, double seconds) {
  // The floor's height under the block: half an ellipsoid, 55.2 mm across and 43.2 mm deep, its
  // lowest point 35.2 mm below the world's origin (tests/support/bowl_scene.hpp).
  const double floor_z = -0.0352 + 0.0432 * (1.0 - std::sqrt(1.0 - place.at.squaredNorm() / (0.0552 * 0.0552)));
  char objects[320];
  std::snprintf(objects, sizeof objects,
                "objects:\n  - {name: block, shape: box, size: [0.01, 0.01, 0.006], mass: 0.005, material: wood, "
                "position: [%.5f, %.5f, %.5f], rpy_deg: [0, 0, %.1f]}\n",
                place.at.x(), place.at.y(), floor_z + 0.0035, place.turn_rad * 180.0 / M_PI);
  std::string text = test::bowlOfBricksScene("bowl", segments, 128, objects);
  const std::string relief = "representation: relief";
  text.replace(text.find(relief), relief.size(), std::string("representation: ") + reading.representation);
  // The scene as physics-client loads it (its surface, mesh and MeshGround's contact options),
  // stepped in a world of the benchmark's own so that the normal map can be read at one point.
  const physclient::PhysicsScene loaded(scene::parseScene(text, "bowl.yaml", "."), physclient::SimOptions{});
  const physclient::MeshGround& ground = *loaded.meshGround();
  phys::MeshContactOptions options = ground.contactOptions();
  if (reading.one_point) options.texture = &loaded.surface().map();
  // A leaning map: read at one point (the code before 2026-12-03), or as MeshGround reads it, the
  // relief its normals integrate to with their mean slope.
  std::optional<tex::TextureMap> leaning;
  std::optional<tex::ReliefOfNormals> relief_of_leaning;
  if (reading.lean != 0.0) {
    leaning = leaned(loaded.surface().map(), reading.lean);
    relief_of_leaning = tex::reliefFromNormals(*leaning, options.normals_made_for_m, loaded.surface().sampling().address);
    options.texture = reading.one_point ? &*leaning : &relief_of_leaning->relief;
    options.relief_mean_slope = reading.one_point ? Eigen::Vector2d::Zero() : relief_of_leaning->mean_slope;
  }
  phys::PhysicsWorld world(physclient::SimOptions{}.world);
  world.addTexturedMesh(ground.sceneMesh().mesh, ground.sceneMesh().mesh_to_world, physclient::materialOf(loaded.scene().surface.material),
                        options);
  const scene::SceneObject& o = loaded.scene().objects.front();
  btRigidBody& block = world.addBox(0.5 * o.size_m, o.mass_kg, scene::toIsometry(o.pose), physclient::materialOf(o.material));
  const int steps = int(std::lround(seconds / 1e-3)), last_second = steps - 1000;
  Cell cell;
  Eigen::Vector3d from = Eigen::Vector3d::Zero();
  for (int k = 1; k <= steps; ++k) {
    world.step(1e-3);
    if (k == last_second) from = phys::toEigen(block.getWorldTransform().getOrigin());
    if (k > last_second) cell.peak_mm_s = std::max(cell.peak_mm_s, 1e3 * phys::toEigen(block.getLinearVelocity()).norm());
  }
  cell.moved_um = 1e6 * (phys::toEigen(block.getWorldTransform().getOrigin()) - from).norm();
  return cell;
}

int run(int argc, char** argv) {
  int segments = 128;
  double seconds = 3.0;
  std::string json, csv, md;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (i + 1 >= argc) throw UsageError(a + " needs a value (see --help)");
    const std::string v = argv[++i];
    if (a == "--segments") segments = int(cli::parseInteger(a, v, 16, 1024));
    else if (a == "--seconds") seconds = cli::parseNumber(a, v, {1.5, 60.0, false, "s"});
    else if (a == "--json") json = v;
    else if (a == "--csv") csv = v;
    else if (a == "--md") md = v;
    else throw UsageError("unknown option " + a + " (see --help)");
  }
  const std::vector<Place> at = places();
  std::vector<std::vector<Cell>> cells;  // [reading][place]
  for (const Reading& reading : kReadings) {
    std::fprintf(stderr, "bench_block_by_pole: %s ...\n", reading.name);
    std::vector<Cell> row;
    for (const Place& p : at) row.push_back(settle(reading, p, segments, seconds));
    cells.push_back(row);
  }
  const std::string stamp = bench::fmt("%s, %s build, %s", bench::isoNow().c_str(), bench::buildType(),
                                       bench::machineSummary().c_str());
  auto atRest = [&](std::size_t r) { return int(std::count_if(cells[r].begin(), cells[r].end(), [](const Cell& c) { return c.atRest(); })); };
  auto worst = [&](std::size_t r) {
    double w = 0;
    for (const Cell& c : cells[r]) w = std::max(w, c.peak_mm_s);
    return w;
  };
  if (!csv.empty()) {
    std::string c = "reading,r_mm,turn_rad,peak_speed_mm_s,moved_um\n";
    for (std::size_t r = 0; r < cells.size(); ++r)
      for (std::size_t k = 0; k < at.size(); ++k)
        c += bench::fmt("%s,%.1f,%.1f,%.4f,%.3f\n", kReadings[r].name, at[k].r_mm, at[k].turn_rad, cells[r][k].peak_mm_s,
                        cells[r][k].moved_um);
    bench::writeTextFile(csv, c);
  }
  if (!json.empty()) {
    std::string j = bench::fmt("{\"stamp\": \"%s\", \"segments\": %d, \"seconds\": %.2f, \"readings\": [", stamp.c_str(), segments, seconds);
    for (std::size_t r = 0; r < cells.size(); ++r) {
      std::string places_json;
      for (std::size_t k = 0; k < at.size(); ++k)
        places_json += bench::fmt("%s{\"r_mm\": %.1f, \"turn_rad\": %.1f, \"peak_speed_mm_s\": %.4f, \"moved_um\": %.3f}", k ? ", " : "",
                                  at[k].r_mm, at[k].turn_rad, cells[r][k].peak_mm_s, cells[r][k].moved_um);
      j += bench::fmt("%s{\"reading\": \"%s\", \"at_rest\": %d, \"places\": [%s]}", r ? ", " : "", kReadings[r].name, atRest(r),
                      places_json.c_str());
    }
    bench::writeTextFile(json, j + "]}\n");
  }
  if (!md.empty()) {
    std::string t = "Measured " + stamp +
                    bench::fmt(". A 10 × 10 × 6 mm, 5 g wooden block set down at %zu places within 17 mm of the floor's centre of "
                               "the bowl of bricks (%d segments; the lathe's uv squeezes the texture towards that centre), "
                               "%.0f s at 1 ms steps: the places where it came to rest (under 0.1 mm/s over the last "
                               "second), the fastest it still moved there, and the fastest at each r, the distance from a "
                               "point 0.76 mm off the centre (the largest of the three turns there).\n\n",
                               at.size(), segments, seconds) +
                    "| reading | at rest | fastest | r = 0 | 2 mm | 4 mm | 7 mm | 10 mm | 13 mm | 16 mm |\n"
                    "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    for (std::size_t r = 0; r < cells.size(); ++r) {
      t += bench::fmt("| %s | %d of %zu | %.2f mm/s |", kReadings[r].name, atRest(r), at.size(), worst(r));
      for (double radius : {0.0, 2.0, 4.0, 7.0, 10.0, 13.0, 16.0}) {
        double peak = 0;
        for (std::size_t k = 0; k < at.size(); ++k)
          if (at[k].r_mm == radius) peak = std::max(peak, cells[r][k].peak_mm_s);
        t += bench::fmt(" %.2f |", peak);
      }
      t += "\n";
    }
    bench::writeTextFile(md, t);
  }
  for (std::size_t r = 0; r < cells.size(); ++r)
    std::printf("%s: at rest at %d of %zu places, fastest %.2f mm/s\n", kReadings[r].name, atRest(r), at.size(), worst(r));
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return bench::benchMain(argc, argv, kHelp, "bench_block_by_pole", run); }
