// A recorded session's hellos against the scene a replaying client loads (thx_client/logged_scene.hpp):
// the check itself, and audio-client and visual-client --replay-log refusing a log whose hello gives
// the scene another texture fingerprint (docs/clients.md §7, docs/audio.md §11).
#include <gtest/gtest.h>

#include <lcm/lcm-cpp.hpp>

#include <cstdint>
#include <string>
#include <vector>

#include <thx_msgs/contact_t.hpp>
#include <thx_msgs/hello_t.hpp>

#include "scenes/scene_loader.hpp"
#include "scenes/scene_surface.hpp"
#include "tests/support/process.hpp"
#include "tests/support/temp_dir.hpp"
#include "textures/smoothing.hpp"
#include "textures/texture_fingerprint.hpp"
#include "thx_client/logged_scene.hpp"
#include "thx_msgs/protocol.hpp"

namespace test_logged_scene {

namespace {

using namespace thx::client;

// A scene with a 32² texture: quick to build in every process of the test.
const std::string kScene = std::string(THX_TEST_DATA_DIR) + "/scenes/balls_collide.yaml";
const std::string kName = "balls_collide";

// The scene's identity as every client computes it (the smoothed texture's fingerprint).
SceneIdentity loaded() {
  const thx::scene::Scene scene = thx::scene::loadScene(kScene);
  thx::scene::SurfaceTextureOptions o;
  o.smooth = thx::tex::smoothTexture;
  const thx::scene::SceneSurface s = thx::scene::buildSceneSurface(scene, o);
  return {s.scene_name, s.fingerprint};
}

template <class M>
void put(lcm::LogFile& log, const std::string& channel, const M& m) {
  std::vector<std::uint8_t> bytes(std::size_t(m.getEncodedSize()));
  m.encode(bytes.data(), 0, int(bytes.size()));
  lcm::LogEvent e{};
  e.timestamp = m.utime;
  e.channel = channel;
  e.datalen = int(bytes.size());
  e.data = bytes.data();
  log.writeEvent(&e);
}

// A session log as hapticd --record writes it: a hello naming `scene` before a few ticks.
void writeSession(const std::string& path, const SceneIdentity& scene) {
  lcm::LogFile log(path, "w");
  thx_msgs::hello_t h{};
  h.utime = 1000;
  h.seq = 1;
  h.protocol_version = thx_msgs::hello_t::PROTOCOL_VERSION;
  h.scene_name = scene.name;
  h.texture_fingerprint = static_cast<std::int64_t>(scene.texture_fingerprint);
  put(log, thx_msgs::kChannelHello, h);
  for (int k = 0; k < 3; ++k) {
    thx_msgs::contact_t c{};
    c.utime = 1000 + 1000 * k;
    c.tick = k;
    c.uv[0] = c.uv[1] = 0.5;
    c.n_geom_world[2] = c.n_sampled_world[2] = 1.0;
    put(log, "THX_CONTACT", c);
  }
}

TEST(LoggedScene, TheRecordedFingerprintMustBeTheLoadedScenes) {
  thx::test::TempDir dir("logged_scene");
  const SceneIdentity mine = loaded();
  writeSession(dir.file("same.lcm"), mine);
  const std::vector<LoggedScene> same = loggedScenes(dir.file("same.lcm"));
  ASSERT_EQ(same.size(), 1u);
  EXPECT_EQ(same[0].utime, 1000);
  EXPECT_EQ(same[0].scene, mine);
  EXPECT_EQ(checkLoggedScene(same, mine, "same.lcm"), "");
  // A hello naming another scene is not this scene's to check.
  EXPECT_EQ(checkLoggedScene({{5, {"default", 0x1}}}, mine, "x.lcm"), "");

  const SceneIdentity edited{mine.name, mine.texture_fingerprint ^ 1};
  const std::vector<LoggedScene> other{{0, mine}, {2000, edited}};
  try {
    checkLoggedScene(other, mine, "other.lcm");
    FAIL() << "a differing fingerprint must be refused";
  } catch (const LoggedSceneMismatch& e) {
    const std::string m = e.what();
    for (const std::string& part : {std::string("other.lcm"), "'" + kName + "'", thx::tex::formatFingerprint(mine.texture_fingerprint),
                                    thx::tex::formatFingerprint(edited.texture_fingerprint), std::string("utime 2000")})
      EXPECT_NE(m.find(part), std::string::npos) << part << " not in: " << m;
  }
  const std::string warning = checkLoggedScene(other, mine, "other.lcm", true);
  EXPECT_NE(warning.find("--allow-different-scene"), std::string::npos) << warning;
}

// Runs a program; its exit status, and its stdout and stderr in `output`.
int runProgram(const thx::test::TempDir& dir, const std::vector<std::string>& argv, std::string& output) {
  const std::string out = dir.file("out.txt");
  const int status = thx::test::reap(thx::test::spawnIn("", argv, out, out), 120.0);
  output = thx::test::slurp(out);
  return status;
}

void expectNamesTheMismatch(const std::string& output, const std::string& log, const SceneIdentity& mine,
                            const SceneIdentity& recorded) {
  EXPECT_NE(output.find(log), std::string::npos) << output;
  EXPECT_NE(output.find("'" + kName + "'"), std::string::npos) << output;
  EXPECT_NE(output.find(thx::tex::formatFingerprint(mine.texture_fingerprint)), std::string::npos) << output;
  EXPECT_NE(output.find(thx::tex::formatFingerprint(recorded.texture_fingerprint)), std::string::npos) << output;
}

TEST(LoggedScene, ReplayingClientsRefuseALogOfAnotherTexture) {
  thx::test::TempDir dir("logged_scene");
  const SceneIdentity mine = loaded();
  const SceneIdentity recorded{mine.name, mine.texture_fingerprint ^ 0x10};
  const std::string log = dir.file("edited.lcm");
  writeSession(log, recorded);
  std::string output;

  EXPECT_EQ(runProgram(dir, {THX_AUDIO_CLIENT, "--scene", kScene, "--replay-log", log, "--wav", dir.file("a.wav"),
                             "--slab-cells", "1", "--no-pen", "--no-cache"},
                       output),
            1);
  expectNamesTheMismatch(output, log, mine, recorded);
  EXPECT_EQ(output.find("modal"), std::string::npos) << "refused before the slab's analysis: " << output;

  EXPECT_EQ(runProgram(dir, {THX_VISUAL_CLIENT, "--scene", kScene, "--replay-log", log, "--out", dir.file("frames")},
                       output),
            1);
  expectNamesTheMismatch(output, log, mine, recorded);
  EXPECT_EQ(output.find("--allow-different-scene"), std::string::npos) << "visual-client has no such option: " << output;

  // Told to differ, audio-client renders it with a warning naming the same.
  EXPECT_EQ(runProgram(dir, {THX_AUDIO_CLIENT, "--scene", kScene, "--replay-log", log, "--wav", dir.file("a.wav"),
                             "--slab-cells", "1", "--no-pen", "--no-cache", "--modes", "8", "--allow-different-scene"},
                       output),
            0)
      << output;
  EXPECT_NE(output.find("warning"), std::string::npos) << output;
  expectNamesTheMismatch(output, log, mine, recorded);
}

}  // namespace

}  // namespace test_logged_scene
