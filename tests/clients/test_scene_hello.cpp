// hapticd announces its scene in hello_t (scene_name, texture_fingerprint), and a client built on
// the same scene file agrees with it while one on another scene is told so, by name and
// fingerprint. hapticd as a process over udpm (skipped without a multicast route).
#include <gtest/gtest.h>

#include <lcm/lcm-cpp.hpp>
#include <optional>

#include "tests/support/hapticd_harness.hpp"
#include "scenes/scene_loader.hpp"
#include "scenes/scene_surface.hpp"
#include "textures/texture_fingerprint.hpp"
#include "thx_client/scene_check.hpp"
#include "thx_msgs/protocol.hpp"

namespace test_scene_hello {

namespace {

using namespace thx;

struct HelloInbox {
  void on(const lcm::ReceiveBuffer* rbuf, const std::string& /*channel*/) {
    thx_msgs::hello_t h;
    if (thx_msgs::try_decode(rbuf->data, rbuf->data_size, h) > 0) hello = h;
  }
  std::optional<thx_msgs::hello_t> hello;
};

client::SceneIdentity identityOf(const std::string& scene_file) {
  const scene::SceneSurface s = scene::buildSceneSurface(scene::loadScene(scene_file));
  return {s.scene_name, s.fingerprint};
}

class SceneHello : public test::HapticdProcessTest {};

TEST_F(SceneHello, HapticdAnnouncesItsSceneAndAClientOnAnotherSceneIsToldBoth) {
  if (!udpmAvailable()) GTEST_SKIP() << "LCM udpm is not available here (" << url_ << "): no multicast route";
  lcm::LCM lcm(url_);
  HelloInbox inbox;
  lcm.subscribe(thx_msgs::kChannelHello, &HelloInbox::on, &inbox);
  startServer({"--scene", "scenes/marble_bricks.yaml", "--quiet"});
  const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (!inbox.hello && std::chrono::steady_clock::now() < end) lcm.handleTimeout(100);
  ASSERT_TRUE(inbox.hello) << "no hello within 30 s; hapticd said:\n" << serverLog();
  const thx_msgs::hello_t& hello = *inbox.hello;

  // A client on another host: the scene by name in its own scenes folder, built the same way.
  const std::string scenes = std::string(THX_SOURCE_DIR) + "/scenes";
  EXPECT_EQ(hello.scene_name, "marble_bricks");
  EXPECT_EQ(hello.protocol_version, thx_msgs::hello_t::PROTOCOL_VERSION);
  EXPECT_EQ(hello.device_names, "Phantom0");  // the scene's one device (protocol 6)
  const client::SceneIdentity mine = identityOf(client::resolveSceneName(hello.scene_name, scenes));
  EXPECT_EQ(static_cast<std::uint64_t>(hello.texture_fingerprint), mine.texture_fingerprint);
  const client::SceneCheck same = client::checkScene(hello, mine, false);
  EXPECT_EQ(same.verdict, client::SceneVerdict::Same) << same.message;

  const client::SceneIdentity other = identityOf(scenes + "/vvalley.yaml");
  const client::SceneCheck differs = client::checkScene(hello, other, false);
  EXPECT_EQ(differs.verdict, client::SceneVerdict::Differs);
  EXPECT_NE(differs.message.find("'marble_bricks'"), std::string::npos) << differs.message;
  EXPECT_NE(differs.message.find("'vvalley'"), std::string::npos) << differs.message;
  EXPECT_NE(differs.message.find(tex::formatFingerprint(mine.texture_fingerprint)), std::string::npos);
  EXPECT_NE(differs.message.find(tex::formatFingerprint(other.texture_fingerprint)), std::string::npos);
  EXPECT_TRUE(client::checkScene(hello, other, /*allow_different_scene=*/true).ok());
  EXPECT_EQ(stopServer(), 0) << serverLog();
}

}  // namespace

}  // namespace test_scene_hello
