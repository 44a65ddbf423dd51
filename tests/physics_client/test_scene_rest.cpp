// Every shipped scene, run with its pen parked (as `physics-client --scene S` before the first
// device state), comes to rest and is then silent: every moving object's speed and every
// contact's reported slip stay below 0.01 mm/s over the half second after its rest time
// (docs/physics.md, "Rest"). The scenes are found in scenes/*.yaml, so a new scene must be
// listed: in kRestBy (with the time by which it is at rest) or, while it is not silent yet, in
// kOpen. Built twice: in physics_client_tests it checks the scenes that rest within a few
// simulated seconds on spheres (fast under the sanitizer too); in physics_client_slow_tests
// (THX_SCENE_REST_SLOW, ctest label `slow`) the boxes on a relief (letter_blocks, grooved_block,
// grooved_board: a box rasterises ~300x slower under ASan) and the zig-zag street (6 s).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "clients/physics_client/physics_scene.hpp"
#include "scenes/scene_loader.hpp"

namespace test_scene_rest {

namespace {

using namespace thx::physclient;

constexpr double kSilent = 1e-5;  // m/s
constexpr double kWindow = 0.5;   // s, measured after the scene's rest time

// Seconds after which each scene is at rest (measured: silent from, printed below, plus margin).
struct RestBy {
  double seconds;
  bool slow;  // checked by the `slow` build only
};
const std::map<std::string, RestBy> kRestBy = {
    {"default", {2.0, false}},         {"dimple_ball", {2.0, false}},
    {"letter_blocks", {2.0, true}},    {"marble_bricks", {2.0, false}},
    {"pen_pushes_ball", {1.0, false}}, {"pen_pushes_ball_dimples", {1.0, false}},
    {"pinball", {3.0, false}},         {"vvalley", {1.0, false}},
    {"zigzag_street", {6.0, true}},    {"brick_bowl", {0.1, false}},
    {"marble_bowl", {2.0, false}},     {"grooved_block", {1.0, true}},
    {"two_pens_two_balls", {1.0, false}}, {"capsule_bricks", {2.0, false}},
    {"two_pens_pinch", {6.0, false}},  {"grooved_block_bowl", {1.0, false}},
    {"dimpled_ball_grooves", {1.0, false}}, {"grooved_board", {2.0, true}},
    {"bumpy_marbles_bowl", {3.0, true}},
};
// Not silent yet (docs/physics.md, "Known gaps"), each with what was measured.
const std::map<std::string, const char*> kOpen = {
    {"marble_rolling_bricks", "rolls on across the joints by design (the audio client's onset check, no rolling friction)"},
    {"two_pens", "no objects: two pens on the bricks (hapticd's several devices), nothing for physics to settle"},
};
#ifdef THX_SCENE_REST_SLOW
constexpr bool kSlowBuild = true;
#else
constexpr bool kSlowBuild = false;
#endif

struct Quiet {
  double max_speed = 0.0, max_slip = 0.0;
  double last_loud_s = 0.0;  // the last time anything moved or slipped above kSilent
};

Quiet runToRest(const std::string& path, double rest_s) {
  // Full-size textures in every build: coarser texels change where and how the objects settle
  // (the letter blocks, slow under the sanitizer, are among the open scenes).
  const thx::scene::Scene scene = thx::scene::loadScene(path);
  // The pen is there (parked, as before hapticd's first state): a kinematic body must not keep
  // resting objects awake.
  PhysicsScene sim(scene, SimOptions{});
  const double dt = 1.0 / scene.rates.physics_hz;
  const auto steps = std::int64_t(std::llround((rest_s + kWindow) / dt));
  Quiet q;
  for (std::int64_t k = 1; k <= steps; ++k) {
    sim.step(dt);
    double speed = 0.0, slip = 0.0;
    for (const BodyState& b : sim.bodies()) speed = std::max(speed, b.v_world.norm());
    for (const LastingContact& c : sim.takeContacts()) slip = std::max(slip, c.v_slip_world.norm());
    if (speed > kSilent || slip > kSilent) q.last_loud_s = double(k) * dt;
    if (double(k) * dt < rest_s) continue;
    q.max_speed = std::max(q.max_speed, speed);
    q.max_slip = std::max(q.max_slip, slip);
  }
  return q;
}

const std::string kScenesDir = std::string(THX_SOURCE_DIR) + "/scenes/";

// Each scene that rests: silent from its rest time on.
class ShippedSceneRest : public ::testing::TestWithParam<std::string> {};

TEST_P(ShippedSceneRest, ComesToRestAndIsSilent) {
  const std::string& name = GetParam();
  const double rest_s = kRestBy.at(name).seconds;
  const Quiet q = runToRest(kScenesDir + name + ".yaml", rest_s);
  std::printf("[measured] %-24s silent from %.3f s; from %.1f s: max speed %.3g m/s, max slip %.3g m/s\n",
              name.c_str(), q.last_loud_s, rest_s, q.max_speed, q.max_slip);
  EXPECT_LT(q.max_speed, kSilent) << name;
  EXPECT_LT(q.max_slip, kSilent) << name;
}

std::vector<std::string> scenesOfThisBuild() {
  std::vector<std::string> names;
  for (const auto& [name, rest] : kRestBy)
    if (rest.slow == kSlowBuild) names.push_back(name);
  return names;
}

INSTANTIATE_TEST_SUITE_P(Scenes, ShippedSceneRest, ::testing::ValuesIn(scenesOfThisBuild()),
                         [](const auto& p) { return p.param; });

// Every scene in scenes/ is either checked above or listed as open.
#ifndef THX_SCENE_REST_SLOW
TEST(ShippedSceneRestList, EverySceneIsCheckedOrListedOpen) {
  int scenes = 0;
  for (const auto& entry : std::filesystem::directory_iterator(kScenesDir)) {
    if (entry.path().extension() != ".yaml") continue;
    const std::string name = entry.path().stem().string();
    EXPECT_TRUE(kRestBy.count(name) + kOpen.count(name) == 1) << "scene " << name << ": add it to kRestBy or kOpen";
    if (kOpen.count(name)) std::printf("[open] %s: %s\n", name.c_str(), kOpen.at(name));
    ++scenes;
  }
  EXPECT_EQ(std::size_t(scenes), kRestBy.size() + kOpen.size());
}
#endif

}  // namespace

}  // namespace test_scene_rest
