// A lasting contact between two objects, end to end as a user runs it (issue 14: every contact
// excites both sides; docs/audio.md §10a): hapticd records a session in lock-step, physics-client
// replays it with a steel ball set down sliding on a steel block (tests/data/scenes/
// ball_on_block.yaml) and records the physics streams into it, audio-client renders the combined
// log with and without the object-contact path (--no-object-contacts). The log holds lasting
// contacts of the ball on the block that slide and then roll; the render sounds them, adds to the
// sound's energy what the impacts alone do not, and gives the same bytes twice. A ball resting on
// the block (ball_resting_on_block.yaml) is reported in contact all along and adds nothing.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <thx_msgs/physics_contacts_t.hpp>

#include "tests/support/rendered_sound.hpp"
#include "thx_msgs/log_reader.hpp"
#include "thx_msgs/protocol.hpp"

namespace test_object_contact_replay {

namespace {

const std::string kScene = std::string(THX_TEST_DATA_DIR) + "/scenes/ball_on_block.yaml";
const std::string kResting = std::string(THX_TEST_DATA_DIR) + "/scenes/ball_resting_on_block.yaml";

class ObjectContactReplay : public thx::test::SessionTest {
 protected:
  // hapticd records 0.3 s of `scene` in lock-step; physics-client replays it with contact reports
  // at 200 Hz (few reports, so the renders stay quick in the sanitizer tree: each report locates
  // the contact point in both meshes) into combined.lcm.
  void simulate(const std::string& scene) {
    ASSERT_EQ(recordSession(scene, "--duration 0.3"), 0);
    ASSERT_EQ(run(std::string(THX_PHYSICS_CLIENT) + " --scene " + scene + " --replay-log " + path("session.lcm") +
                  " --duration 0.3 --contact-rate 200 --record " + path("combined.lcm") + " --no-lcm --quiet > " +
                  path("physics.out")),
              0)
        << fileBytes(path("physics.out"));
  }
  // audio-client renders combined.lcm with `options` to `wav` (small meshes and few modes: quick in
  // the sanitizer tree, both bodies keep audible modes); its output.
  std::string audio(const std::string& scene, const std::string& options, const std::string& wav) {
    const std::string out = path(wav + ".out");
    EXPECT_EQ(run(std::string(THX_AUDIO_CLIENT) + " --scene " + scene + " --replay-log " + path("combined.lcm") +
                  " --slab-cells 2 --modes 12 --object-elements tet4 --no-pen --cache-dir " + path("cache") + options +
                  " --wav " + path(wav) + " > " + out + " 2>&1"),
              0)
        << fileBytes(out);
    return fileBytes(out);
  }
  // audio-client's summary: the number after `label` on its physics line (-1: not found).
  static double number(const std::string& out, const std::string& label) {
    const std::size_t at = out.find(label);
    return at == std::string::npos ? -1.0 : std::stod(out.substr(at + label.size()));
  }
};

TEST_F(ObjectContactReplay, ABallSlidingOnABlockSoundsInTheOfflineRender) {
  simulate(kScene);
  if (HasFatalFailure()) return;

  // The ball (0) on the block (1): reported every 5 ms, first sliding, then (almost) rolling.
  std::size_t reports = 0, sliding = 0, rolling = 0;
  double max_force = 0.0;
  thx_msgs::forEachLogMessage<thx_msgs::physics_contacts_t>(
      path("combined.lcm"), thx_msgs::kChannelPhysicsContacts, [&](const auto& m, const auto&) {
        for (int k = 0; k < m.num_contacts; ++k) {
          if (m.body_a[k] != 0 || m.body_b[k] != 1) continue;
          ++reports;
          const double slip = std::hypot(m.v_slip_world[k][0], m.v_slip_world[k][1], m.v_slip_world[k][2]);
          const double v = std::hypot(m.v_world[k][0], m.v_world[k][1]);
          sliding += slip > 0.05;
          rolling += slip < 0.01 && v > 0.05;
          max_force = std::max(max_force, m.f_normal[k]);
        }
      });
  std::printf("[measured] ball on block: %zu reports, %zu sliding (slip > 5 cm/s), %zu rolling (slip < 1 cm/s), "
              "normal force up to %.4g N\n", reports, sliding, rolling, max_force);
  ASSERT_GT(reports, 40u) << fileBytes(path("physics.out"));
  EXPECT_GT(sliding, 0u);
  EXPECT_GT(rolling, 0u);

  const std::string with = audio(kScene, "", "with.wav"), again = audio(kScene, "", "again.wav"),
                    without = audio(kScene, " --no-object-contacts", "without.wav");
  std::printf("%s%s", with.c_str(), without.c_str());
  const double segments = number(with, "relief impulses, ");
  EXPECT_GT(segments, 0.5 * double(reports)) << with;
  EXPECT_EQ(number(without, "relief impulses, "), 0.0) << without;
  // The energy of the physics streams' raw modal displacements: the contact adds to the impacts'.
  const double e_with = number(with, "physics energy "), e_without = number(without, "physics energy ");
  std::printf("[measured] physics energy with the object contacts %.4g, without %.4g (ratio %.3f)\n", e_with, e_without,
              e_with / e_without);
  EXPECT_GT(e_without, 0.0) << without;
  EXPECT_GT(e_with, 1.01 * e_without);
  // Deterministic: the same log, the same bytes.
  EXPECT_EQ(fileBytes(path("with.wav")), fileBytes(path("again.wav")));
  EXPECT_NE(fileBytes(path("with.wav")), fileBytes(path("without.wav")));
}

// The ball set down at rest on the block: the pair is reported all along, but nothing moves at the
// contact (beyond the engine's settling, below the rest threshold), so this path adds nothing:
// the render is the same bytes with it and without it.
TEST_F(ObjectContactReplay, ABallRestingOnABlockAddsNothing) {
  simulate(kResting);
  if (HasFatalFailure()) return;
  std::size_t reports = 0;
  thx_msgs::forEachLogMessage<thx_msgs::physics_contacts_t>(path("combined.lcm"), thx_msgs::kChannelPhysicsContacts,
                                                             [&](const auto& m, const auto&) {
                                                               for (int k = 0; k < m.num_contacts; ++k)
                                                                 reports += m.body_a[k] == 0 && m.body_b[k] == 1;
                                                             });
  std::printf("[measured] ball resting on the block: %zu reports\n", reports);
  ASSERT_GT(reports, 40u) << fileBytes(path("physics.out"));
  const std::string with = audio(kResting, "", "with.wav"), without = audio(kResting, " --no-object-contacts", "without.wav");
  std::printf("%s", with.c_str());
  EXPECT_EQ(number(with, "relief impulses, "), 0.0) << with;
  EXPECT_EQ(fileBytes(path("with.wav")), fileBytes(path("without.wav")));
}

}  // namespace

}  // namespace test_object_contact_replay
