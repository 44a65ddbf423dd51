// What a textured object costs a physics step when the pen or another object meets it (issue 29;
// clients/physics/ball_on_object_faces.hpp, box_ground.hpp): the same scene with the object plain
// and textured, each the median of three runs. Measures only; nothing asserted
// (tests/physics/test_capsule_on_box_faces.cpp, test_ball_on_textured_ball.cpp and
// test_textured_ball_pairs.cpp hold the behaviour).
#include <algorithm>
#include <array>
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
#include "tests/physics/textured_ball_scene.hpp"

namespace {

using namespace thx;
using namespace thx::phys;
using namespace thx::phys::test;

constexpr const char* kHelp = R"(usage: bench_pen_on_objects [--steps N] [--json F] [--csv F] [--md F]

The time of a whole world's physics step (1 ms) in six scenes, each with its object plain and
textured, the median of three runs of N steps (default 400):
  pen on a block    the pen's capsule (4 mm, upright, kinematic) pressing a 2 x 2 x 1 cm, 50 g
                    block on a plain plane at 20 mm/s: plain, or with V-grooves 4 mm apart and
                    1 mm deep on its faces (0.31 mm texels), upright on the face the pen meets;
  block on the plane  the same block resting on the plain plane, kept awake, no pen (a textured
                    object meets the plain plane by its texture: the step's floor share above);
  pen on a ball     the same pen pressing a 1 cm, 30 g ball's side: plain, or with the shipped
                    dimples (3.9 mm apart, 0.25 mm deep, 61 um texels);
  ball on the plane  the same ball resting on the plain plane, kept awake, no pen;
  marble on a ball  a 3 mm marble resting in the top dimple of a fixed 1 cm ball, plain or dimpled;
  ball on a ball    a 1 cm ball resting on a fixed one: both plain, or both dimpled.
Each step's time includes Bullet's broadphase, detection and solver for the whole world.

  --steps N       steps per run (default 400)
  --json/--csv/--md F   results
)";

enum class Scene { PenOnBlock, BlockOnPlane, PenOnBall, BallOnPlane, MarbleOnBall, BallOnBall };
constexpr std::array<Scene, 6> kScenes{Scene::PenOnBlock, Scene::BlockOnPlane, Scene::PenOnBall,
                                       Scene::BallOnPlane,  Scene::MarbleOnBall, Scene::BallOnBall};

const char* nameOf(Scene s) {
  switch (s) {
    case Scene::PenOnBlock: return "pen on a block";
    case Scene::BlockOnPlane: return "block on the plane";
    case Scene::PenOnBall: return "pen on a ball";
    case Scene::BallOnPlane: return "ball on the plane";
    case Scene::MarbleOnBall: return "marble on a ball";
    case Scene::BallOnBall: return "ball on a ball";
  }
  return "";
}

struct Row {
  std::string scene;
  double plain_us = 0, textured_us = 0;
};

// One run: microseconds per step, over `steps` steps after 20 to settle the first contacts.
double runOnce(Scene scene, bool textured, int steps) {
  const tex::TextureMap grooves = heightMap(128, grooved_block::kExtent, grooved_block::vGrooves);
  const tex::TextureMap dimples = textured_ball::dimpleMap();
  FaceTexture block_faces;
  block_faces.map = &grooves;
  block_faces.tile_m = grooved_block::kExtent;
  const FaceTexture ball_faces = textured_ball::ballTexture(dimples);
  PhysicsWorld world;
  const double kR = textured_ball::kRadius;
  btRigidBody* pen = nullptr;
  Eigen::Vector3d pen_velocity = Eigen::Vector3d::Zero();
  const bool block = scene == Scene::PenOnBlock || scene == Scene::BlockOnPlane;
  const bool with_pen = scene == Scene::PenOnBlock || scene == Scene::PenOnBall;
  const Eigen::Vector3d half(0.01, 0.01, 0.005);  // the block's
  if (block || scene == Scene::PenOnBall || scene == Scene::BallOnPlane) {
    world.addPlainPlane(Eigen::Isometry3d::Identity(), {0.5, 0.0, 0.0});
    btRigidBody* object = nullptr;
    if (block) {
      // The grooves vary along the face texture's u, which runs along y on the +x face: upright there.
      object = textured ? &world.addTexturedBox(half, 0.05, at(0.0, 0.0, half.z()), {0.5, 0.0, 0.0}, block_faces)
                        : &world.addBox(half, 0.05, at(0.0, 0.0, half.z()), {0.5, 0.0, 0.0});
    } else {
      object = textured ? &world.addTexturedSphere(kR, 0.03, at(0.0, 0.0, kR), {0.5, 0.0, 0.0}, ball_faces)
                        : &world.addSphere(kR, 0.03, at(0.0, 0.0, kR), {0.5, 0.0, 0.0});
    }
    if (!with_pen) object->setActivationState(DISABLE_DEACTIVATION);  // timed awake, as while something moves it
  }
  if (with_pen) {
    // The block's side, its lower ball's centre the tip 2 mm over the plane; or the ball's equator.
    const double face_x = block ? half.x() : kR, pen_z = block ? 0.006 : kR;
    constexpr double kPenRadius = 0.004, kPenHalf = 0.008;
    // Upright, just clear of the object's side, moving into it.
    pen = &world.addCapsule(kPenRadius, kPenHalf, 0.0, at(face_x + kPenRadius + 1e-4, 0.0, pen_z + kPenHalf), {0.0, 0.0, 0.0});
    pen_velocity = Eigen::Vector3d(-0.02, 0.0, 0.0);
    pen->setCollisionFlags(pen->getCollisionFlags() | btCollisionObject::CF_KINEMATIC_OBJECT);
    pen->setActivationState(DISABLE_DEACTIVATION);
  } else if (scene == Scene::MarbleOnBall || scene == Scene::BallOnBall) {
    const double r = scene == Scene::MarbleOnBall ? 0.003 : kR;
    if (textured)
      world.addTexturedSphere(kR, 0.0, Eigen::Isometry3d::Identity(), {0.5, 0.0, 0.0}, ball_faces);
    else
      world.addSphere(kR, 0.0, Eigen::Isometry3d::Identity(), {0.5, 0.0, 0.0});
    // In the top dimple (its floor 0.25 mm down; the rims hold a 1 cm ball 0.13 mm up), falling
    // 0.1 mm onto it, held to the vertical line.
    const double rest = kR + r - (scene == Scene::MarbleOnBall ? 0.25e-3 : 0.13e-3);
    btRigidBody& body =
        textured && scene == Scene::BallOnBall
            ? world.addTexturedSphere(r, 0.03, at(0.0, 0.0, rest + 1e-4), {0.5, 0.0, 0.0}, ball_faces)
            : world.addSphere(r, scene == Scene::MarbleOnBall ? 0.3e-3 : 0.03, at(0.0, 0.0, rest + 1e-4), {0.5, 0.0, 0.0});
    body.setLinearFactor(btVector3(0, 0, 1));
    body.setAngularFactor(btVector3(0, 0, 0));
    body.setActivationState(DISABLE_DEACTIVATION);  // timed awake, as while something moves it
  }
  constexpr double dt = 1e-3;
  const auto advance = [&] {
    if (pen) {
      btTransform t = pen->getWorldTransform();
      t.setOrigin(t.getOrigin() + toBt(Eigen::Vector3d(pen_velocity * dt)));
      pen->setWorldTransform(t);
    }
    world.step(dt);
  };
  for (int k = 0; k < 20; ++k) advance();
  const auto t0 = std::chrono::steady_clock::now();
  for (int k = 0; k < steps; ++k) advance();
  const auto t1 = std::chrono::steady_clock::now();
  return std::chrono::duration<double, std::micro>(t1 - t0).count() / double(steps);
}

double median3(Scene scene, bool textured, int steps) {
  std::array<double, 3> runs{};
  for (double& r : runs) r = runOnce(scene, textured, steps);
  std::sort(runs.begin(), runs.end());
  return runs[1];
}

int run(int argc, char** argv) {
  int steps = 400;
  std::string json, csv, md;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (i + 1 >= argc) throw UsageError(a + " needs a value (see --help)");
    const std::string v = argv[++i];
    if (a == "--steps") steps = int(cli::parseInteger(a, v, 1, 1000000));
    else if (a == "--json") json = v;
    else if (a == "--csv") csv = v;
    else if (a == "--md") md = v;
    else throw UsageError("unknown option " + a + " (see --help)");
  }
  std::vector<Row> rows;
  for (const Scene scene : kScenes) {
    std::fprintf(stderr, "bench_pen_on_objects: %s ...\n", nameOf(scene));
    rows.push_back({nameOf(scene), median3(scene, false, steps), median3(scene, true, steps)});
  }
  const std::string stamp = bench::fmt("%s, %s build, %s", bench::isoNow().c_str(), bench::buildType(),
                                       bench::machineSummary().c_str());
  if (!csv.empty()) {
    std::string c = "scene,plain_us_per_step,textured_us_per_step\n";
    for (const Row& r : rows) c += bench::fmt("%s,%.2f,%.2f\n", r.scene.c_str(), r.plain_us, r.textured_us);
    bench::writeTextFile(csv, c);
  }
  if (!json.empty()) {
    std::string j = bench::fmt("{\"stamp\": \"%s\", \"steps\": %d, \"rows\": [", stamp.c_str(), steps);
    for (std::size_t k = 0; k < rows.size(); ++k)
      j += bench::fmt("%s{\"scene\": \"%s\", \"plain_us_per_step\": %.3f, \"textured_us_per_step\": %.3f}", k ? ", " : "",
                      rows[k].scene.c_str(), rows[k].plain_us, rows[k].textured_us);
    bench::writeTextFile(json, j + "]}\n");
  }
  if (!md.empty()) {
    std::string t = "Measured " + stamp +
                    bench::fmt(". A whole world's 1 ms step, the median of three runs of %d steps: the pen's capsule "
                               "pressing a block's side (plain, or V-grooves upright on that face) and a ball's side "
                               "(plain, or the shipped dimples), each on a plain plane, and each of them alone on the "
                               "plane, kept awake (a textured object meets the plane by its texture); a 3 mm marble in "
                               "a fixed ball's top dimple; a 1 cm ball on a fixed one (both plain, or both dimpled).\n\n",
                               steps) +
                    "| scene | plain | textured | ratio |\n|---|---:|---:|---:|\n";
    for (const Row& r : rows)
      t += bench::fmt("| %s | %.1f µs | %.1f µs | %.1f× |\n", r.scene.c_str(), r.plain_us, r.textured_us,
                      r.textured_us / r.plain_us);
    bench::writeTextFile(md, t);
  }
  for (const Row& r : rows)
    std::printf("%-18s plain %8.1f us, textured %8.1f us a step (%.1fx)\n", r.scene.c_str(), r.plain_us, r.textured_us,
                r.textured_us / r.plain_us);
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return bench::benchMain(argc, argv, kHelp, "bench_pen_on_objects", run); }
