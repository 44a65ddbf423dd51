// A marble in a bowl of bricks, heard (issue 29): hapticd records a mesh scene in lock-step,
// physics-client replays it with the marble rolling down the bowl's inside and records its
// streams into it, audio-client renders the combined log. The bowl sounds as the solid its mesh
// encloses (Gmsh, scene_mesh_body.hpp), struck where the physics client's contacts are, moved
// into the mesh's frame. The pen stroking the bowl's floor scrapes that solid too, offline and
// live alike (synthesis/scrape_sites.hpp).
#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <vector>

#include <thx_msgs/contact_t.hpp>
#include <thx_msgs/physics_impact_t.hpp>

#include "base/error.hpp"
#include "clients/audio/analysis/scene_mesh_body.hpp"
#include "clients/audio/live/live_scene.hpp"
#include "clients/audio/synthesis/scrape_sites.hpp"
#include "tests/support/bowl_scene.hpp"
#include "tests/support/rendered_sound.hpp"
#include "thx_msgs/log_reader.hpp"
#include "thx_msgs/protocol.hpp"

namespace test_mesh_sound_replay {

namespace {

struct Events final : thx::audio::ExcitationSink {
  std::vector<thx::audio::ExcitationEvent> all;
  void push(const thx::audio::ExcitationEvent& e) override { all.push_back(e); }
};

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
  EXPECT_NE(out.find("a mesh surface: the pen and the physics client's contacts strike the solid its mesh encloses"),
            std::string::npos)
      << out;
  EXPECT_EQ(out.find("physics: 0 impacts"), std::string::npos) << out;
  EXPECT_FALSE(thx::test::wavOnsets(path("a.wav"), 0.2).empty()) << "no sound in " << path("a.wav");
  // The same render again: the same bytes (the bowl's modes from the cache this time).
  ASSERT_EQ(run(render + path("b.wav") + " > " + path("audio_b.out") + " 2>&1"), 0) << fileBytes(path("audio_b.out"));
  EXPECT_TRUE(fileBytes(path("a.wav")) == fileBytes(path("b.wav")));
}

// The pen strokes the bowl's floor across the bricks' joints (the bowl's frame, 3.5 cm under the
// device's origin), no objects.
const std::string kStrokeScene = thx::test::bowlOfBricksScene("stroke_in_a_bowl", 12, 64, R"(device:
  type: sim
  model: phantom_desktop
  script:
    - hold: {duration: 0.1}
    - stroke: {from: [-0.012, 0.003], to: [0.012, -0.003], speed: 0.04, force: 0.6}
rates: {servo_hz: 1000, physics_hz: 1000}
)");

std::size_t numberAfter(const std::string& text, const std::string& before_it) {
  const std::size_t at = text.find(before_it);
  return at == std::string::npos ? 0 : std::stoul(text.substr(at + before_it.size()));
}

// The relief's impulses strike the bowl's solid offline; live, the same samples through the live
// client's pen source strike the same number of times, each at a surface node of the solid and
// along that node's outward normal. Without a way to fill the mesh (a program that does not link
// Gmsh) the live scene is refused by name.
TEST_F(MeshSoundReplay, ThePensScrapeOnTheBowlSoundsOfflineAndLiveAlike) {
  const std::string scene = path("stroke_in_a_bowl.yaml");
  std::ofstream(scene) << kStrokeScene;
  ASSERT_EQ(recordSession(scene, "--duration 1.5"), 0) << fileBytes(path("hapticd.out"));
  const std::string render = std::string(THX_AUDIO_CLIENT) + " --scene " + scene + " --replay-log " + path("session.lcm") +
                             " --modes 12 --no-pen --cache-dir " + path("cache") + " --wav " + path("a.wav") + " > " +
                             path("audio.out") + " 2>&1";
  ASSERT_EQ(run(render), 0) << fileBytes(path("audio.out"));
  const std::string out = fileBytes(path("audio.out"));
  std::printf("%s", out.c_str());
  const std::size_t struck = numberAfter(out, "relief impulses (");
  EXPECT_GT(struck, 20u) << out;
  EXPECT_FALSE(thx::test::wavOnsets(path("a.wav"), 0.2).empty()) << "no sound in " << path("a.wav");

  thx::audio::LiveSceneSettings settings;
  settings.slab.cache_dir = path("cache");
  settings.slab.modes = 12;
  settings.slab.quiet = true;
  settings.pen_modes = false;
  try {
    thx::audio::buildLiveScene(scene, settings, 1);
    FAIL() << "no error";
  } catch (const thx::Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("stroke_in_a_bowl.yaml"), std::string::npos) << what;
    EXPECT_NE(what.find("sounded by the audio-client program"), std::string::npos) << what;
  }
  settings.mesh_body = [](const thx::scene::Scene& s) { return thx::audio::meshSurfaceBody(s); };
  const std::unique_ptr<thx::audio::LiveScene> live = thx::audio::buildLiveScene(scene, settings, 1);
  ASSERT_TRUE(live->sound->mesh_to_world.has_value());
  const thx::audio::ScrapeSites sites = thx::audio::ScrapeSites::meshSurface(live->sound->slab, *live->sound->mesh_to_world);
  Events events;
  thx_msgs::forEachLogMessage<thx_msgs::contact_t>(path("session.lcm"), "THX_CONTACT", [&](const auto& c, const auto&) {
    live->sources.front()->penContact(c, 0, events);
  });
  std::size_t impulses = 0;
  for (const thx::audio::ExcitationEvent& e : events.all) {
    if (e.body != 0 || e.kind != thx::audio::ExcitationKind::Impulse) continue;
    ++impulses;
    const Eigen::Vector3d j(e.impulse[0], e.impulse[1], e.impulse[2]);
    const Eigen::Vector3d& n = sites.direction(e.node);
    ASSERT_NEAR(n.norm(), 1.0, 1e-12) << "node " << e.node << " is not on the solid's surface";
    EXPECT_LT(j.cross(n).norm(), 1e-12 * j.norm()) << e.node;
  }
  EXPECT_EQ(impulses, struck);
}

}  // namespace

}  // namespace test_mesh_sound_replay
