// Every shipped scene, run with its pen parked (as `physics-client --scene S` before the first
// device state), comes to rest and is then silent: every moving object's speed and every
// contact's reported slip stay below 0.01 mm/s over the last half second (docs/physics.md, "Rest"). The scenes are found in
// scenes/*.yaml, so a new scene must be listed: in kRestBy (when it is at rest) or, while it is
// not silent yet, in kOpen.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>

#include "clients/physics_client/physics_scene.hpp"
#include "scenes/scene_loader.hpp"

namespace {

using namespace thx::physclient;

constexpr double kSilent = 1e-5;  // m/s
constexpr double kWindow = 0.5;   // s, measured after the scene's rest time

// Seconds after which each scene is at rest (measured: the last object asleep, plus margin).
const std::map<std::string, double> kRestBy = {
    {"marble_bricks", 2.0}, {"pen_pushes_ball", 1.0}, {"pen_pushes_ball_dimples", 1.0},
    {"pinball", 4.0},       {"vvalley", 1.0},
};
// Not silent yet (docs/physics.md, "Known gaps"), each with what was measured:
//  dimple_ball   -- the ball rolls in place in a dimple of its radius (2.3 mm/s read);
//  default       -- the marble (no rolling friction) ends in a dip spinning about the vertical at
//                   0.17 rad/s, its off-axis contact slipping 0.13 mm/s;
//  letter_blocks -- the blocks against the fence rock on the pebbles (0.5-0.9 rad/s, 2 mm/s) at 8 s;
//  zigzag_street -- the balls at the kerb creep at up to 0.4 mm/s at 15 s;
//  marble_rolling_bricks -- rolls on across the joints on purpose (the audio client's onset check).
const std::map<std::string, const char*> kOpen = {
    {"dimple_ball", "rolls in place"}, {"default", "spins in place, slip 0.13 mm/s"},
    {"letter_blocks", "rocks at the fence, 2 mm/s"}, {"zigzag_street", "creeps at the kerb, 0.4 mm/s"},
    {"marble_rolling_bricks", "rolls on by design (no rolling friction)"},
};


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
  const Quiet q = runToRest(kScenesDir + name + ".yaml", kRestBy.at(name));
  std::printf("[measured] %-24s silent from %.3f s; from %.1f s: max speed %.3g m/s, max slip %.3g m/s\n",
              name.c_str(), q.last_loud_s, kRestBy.at(name), q.max_speed, q.max_slip);
  EXPECT_LT(q.max_speed, kSilent) << name;
  EXPECT_LT(q.max_slip, kSilent) << name;
}

INSTANTIATE_TEST_SUITE_P(Scenes, ShippedSceneRest,
                         ::testing::Values("marble_bricks", "pen_pushes_ball", "pen_pushes_ball_dimples", "pinball",
                                           "vvalley"),
                         [](const auto& p) { return p.param; });

// Every scene in scenes/ is either checked above or listed as open.
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

}  // namespace
