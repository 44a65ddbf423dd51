// Two objects striking each other, end to end as a user runs it (issue 14: every contact excites
// both sides): hapticd records a session in lock-step, physics-client replays it with two large
// steel balls (tests/data/scenes/balls_collide.yaml: the 10 cm ball rolls into the 13 cm one) and
// records the physics streams into it, audio-client renders the combined log. The log holds one
// impact naming both balls; the render sounds it on both (docs/audio.md §9, §11). (Two renders
// giving the same bytes: MarbleOnBricks; the same samples from the same streams: PhysicsSound.)
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include <thx_msgs/physics_impact_t.hpp>

#include "tests/support/rendered_sound.hpp"
#include "thx_msgs/log_reader.hpp"
#include "thx_msgs/protocol.hpp"

namespace test_object_impact_replay {

namespace {

const std::string kScene = std::string(THX_TEST_DATA_DIR) + "/scenes/balls_collide.yaml";

class ObjectImpactReplay : public thx::test::SessionTest {};

TEST_F(ObjectImpactReplay, ABallStrikingABallSoundsInTheOfflineRender) {
  ASSERT_EQ(recordSession(kScene, "--duration 0.6"), 0);
  ASSERT_EQ(run(std::string(THX_PHYSICS_CLIENT) + " --scene " + kScene + " --replay-log " + path("session.lcm") +
                " --record " + path("combined.lcm") + " --no-lcm --quiet > " + path("physics.out")),
            0)
      << fileBytes(path("physics.out"));

  // The impact of the two balls: a = the rolling one (index 0), b = the one at rest, the normal
  // from b's centre to a's, the impulse less than an elastic impact of the 10 cm ball (32.9 kg) at
  // 0.3 m/s could give.
  std::vector<thx_msgs::physics_impact_t> between;
  thx_msgs::forEachLogMessage<thx_msgs::physics_impact_t>(path("combined.lcm"), thx_msgs::kChannelPhysicsImpact,
                                                           [&](const auto& m, const auto&) {
                                                             if (m.body_a >= 0 && m.body_b >= 0) between.push_back(m);
                                                           });
  ASSERT_EQ(between.size(), 1u) << fileBytes(path("physics.out"));
  const thx_msgs::physics_impact_t& hit = between[0];
  EXPECT_EQ(hit.body_a, 0);
  EXPECT_EQ(hit.body_b, 1);
  EXPECT_FALSE(hit.on_surface);
  // The centres 0.23 m apart, 0.03 m apart in height: n = (-sqrt(0.23² - 0.03²), 0, -0.03) / 0.23.
  EXPECT_NEAR(hit.n_world[0], -0.99145, 2e-3);
  EXPECT_NEAR(hit.n_world[1], 0.0, 1e-3);
  EXPECT_NEAR(hit.n_world[2], -0.13043, 2e-3);
  EXPECT_GT(hit.impulse, 0.0);
  EXPECT_LT(hit.impulse, 2.0 * 32.9 * 0.3);
  std::printf("[measured] ball on ball: impulse %.4g N s at %.3f s, approach %.4g m/s\n", hit.impulse, hit.sim_time,
              hit.v_approach);

  // Small meshes and few modes: quick in the sanitizer tree (each ball keeps audible modes).
  const std::string render = std::string(THX_AUDIO_CLIENT) + " --scene " + kScene + " --replay-log " + path("combined.lcm") +
                             " --slab-cells 2 --modes 12 --object-elements tet4 --no-pen --cache-dir " + path("cache") + " --wav ";
  ASSERT_EQ(run(render + path("a.wav") + " > " + path("audio.out") + " 2>&1"), 0) << fileBytes(path("audio.out"));
  const std::string out = fileBytes(path("audio.out"));
  std::printf("%s", out.c_str());
  EXPECT_NE(out.find("(1 between two objects;"), std::string::npos) << out;
  EXPECT_FALSE(thx::test::wavOnsets(path("a.wav"), 0.2).empty()) << "no sound in " << path("a.wav");
}

}  // namespace

}  // namespace test_object_impact_replay
