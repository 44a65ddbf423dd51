// A marble in a bowl of bricks, heard (issue 29): hapticd records a mesh scene in lock-step,
// physics-client replays it with the marble rolling down the bowl's inside and records its
// streams into it, audio-client renders the combined log. The bowl sounds as the solid its mesh
// encloses (Gmsh, scene_mesh_body.hpp), struck where the physics client's contacts are, moved
// into the mesh's frame; the pen's scrape on a mesh is not rendered yet, and says so.
#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <vector>

#include <thx_msgs/physics_impact_t.hpp>

#include "base/error.hpp"
#include "clients/audio/live/live_scene.hpp"
#include "tests/support/bowl_scene.hpp"
#include "tests/support/rendered_sound.hpp"
#include "thx_msgs/log_reader.hpp"
#include "thx_msgs/protocol.hpp"

namespace test_mesh_sound_replay {

namespace {

// A coarse bowl (12 segments, as sounded), a coarse texture, one steel marble on its inside wall;
// the pen holds above the rim.
const std::string kScene = thx::test::bowlOfBricksScene("marble_in_a_bowl", 12, 32, R"(device:
  type: sim
  model: phantom_desktop
  script:
    - hold: {duration: 0.6}
objects:
  - {name: marble, shape: sphere, radius: 0.006, mass: 0.007, material: steel, position: [0.03, 0.0, -0.018]}
rates: {servo_hz: 1000, physics_hz: 1000}
)");

class MeshSoundReplay : public thx::test::SessionTest {};

TEST_F(MeshSoundReplay, AMarbleInABowlStrikesTheBowlsOwnModes) {
  const std::string scene = path("marble_in_a_bowl.yaml");
  std::ofstream(scene) << kScene;
  ASSERT_EQ(recordSession(scene, "--duration 0.6"), 0) << fileBytes(path("hapticd.out"));
  ASSERT_EQ(run(std::string(THX_PHYSICS_CLIENT) + " --scene " + scene + " --replay-log " + path("session.lcm") +
                " --record " + path("combined.lcm") + " --no-lcm --quiet > " + path("physics.out")),
            0)
      << fileBytes(path("physics.out"));
  // The marble lands on the bowl's inside wall: impacts on the surface.
  std::size_t on_surface = 0;
  thx_msgs::forEachLogMessage<thx_msgs::physics_impact_t>(path("combined.lcm"), thx_msgs::kChannelPhysicsImpact,
                                                           [&](const auto& m, const auto&) { on_surface += m.on_surface != 0; });
  ASSERT_GT(on_surface, 0u) << fileBytes(path("physics.out"));

  const std::string render = std::string(THX_AUDIO_CLIENT) + " --scene " + scene + " --replay-log " + path("combined.lcm") +
                             " --modes 12 --object-elements tet4 --no-pen --cache-dir " + path("cache") + " --wav ";
  ASSERT_EQ(run(render + path("a.wav") + " > " + path("audio.out") + " 2>&1"), 0) << fileBytes(path("audio.out"));
  const std::string out = fileBytes(path("audio.out"));
  std::printf("%s", out.c_str());
  EXPECT_NE(out.find("a mesh surface: the physics client's contacts strike the solid its mesh encloses"), std::string::npos)
      << out;
  EXPECT_NE(out.find("the pen's scrape on a mesh is not rendered yet"), std::string::npos) << out;
  EXPECT_EQ(out.find("physics: 0 impacts"), std::string::npos) << out;
  EXPECT_FALSE(thx::test::wavOnsets(path("a.wav"), 0.2).empty()) << "no sound in " << path("a.wav");
  // The same render again: the same bytes (the bowl's modes from the cache this time).
  ASSERT_EQ(run(render + path("b.wav") + " > " + path("audio_b.out") + " 2>&1"), 0) << fileBytes(path("audio_b.out"));
  EXPECT_TRUE(fileBytes(path("a.wav")) == fileBytes(path("b.wav")));
}

// Live, the pen's scrape would strike a slab's top face a mesh has not: the live client refuses a
// mesh scene by name, before any analysis (offline renders it, above).
TEST_F(MeshSoundReplay, TheLiveClientRefusesAMeshSceneByName) {
  const std::string scene = path("marble_in_a_bowl.yaml");
  std::ofstream(scene) << kScene;
  try {
    thx::audio::buildLiveScene(scene, thx::audio::LiveSceneSettings{}, 1);
    FAIL() << "no error";
  } catch (const thx::Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("marble_in_a_bowl.yaml"), std::string::npos) << what;
    EXPECT_NE(what.find("audio-client live"), std::string::npos) << what;
    EXPECT_NE(what.find("sounded offline by audio-client from a recording"), std::string::npos) << what;
  }
}

}  // namespace

}  // namespace test_mesh_sound_replay
