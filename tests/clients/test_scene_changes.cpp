// The server's scene as the kit follows it (Client::serverScene, sceneChanges, onSceneChange) from
// the fake hapticd's hellos over memq://: a switch within one server instance is a change; the
// first hello, repeated hellos and a restart on the same scene are not; a restart on another scene
// is (flagged as a restart); a hello older than the newest cannot switch back; two switches
// between polls count twice and leave the newest. One process, no clock involved.
#include <gtest/gtest.h>

#include <lcm/lcm-cpp.hpp>
#include <memory>
#include <thx_msgs/protocol.hpp>
#include <vector>

#include "tests/support/fake_server.hpp"
#include "thx_client/client.hpp"

namespace test_scene_changes {

using namespace thx;
using client::Client;
using client::SceneChange;
using client::SceneIdentity;
using test::FakeServer;

namespace {

class SceneChanges : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(lcm_.good());
    client::ClientOptions o;
    o.client_id = "follower";
    o.clock = [this] { return now_; };
    client_ = std::make_unique<Client>(lcm_, o);
    client_->onSceneChange([this](const SceneChange& c) { changes_.push_back(c); });
  }
  void pump() {
    for (int k = 0; k < 4; ++k) client_->poll(0);
  }
  std::string scene() const { return client_->serverScene() ? client_->serverScene()->name : "<none>"; }

  lcm::LCM lcm_{"memq://"};
  std::int64_t now_ = 1'000'000'000;
  std::unique_ptr<Client> client_;
  std::vector<SceneChange> changes_;
};

}  // namespace

TEST_F(SceneChanges, ASwitchWithinAnInstanceIsAChangeAndRepeatsAreNot) {
  FakeServer server(lcm_, 5, now_);
  server.scene_name = "marble_bricks";
  server.texture_fingerprint = 0x10;
  EXPECT_FALSE(client_->serverScene());
  server.hello();
  pump();
  EXPECT_EQ(scene(), "marble_bricks");  // the first hello tells the scene, changes nothing
  EXPECT_EQ(client_->serverScene()->texture_fingerprint, 0x10u);
  server.hello();
  server.hello();
  pump();
  EXPECT_EQ(client_->sceneChanges(), 0u);

  server.switchScene("vvalley", 0x20);
  pump();
  EXPECT_EQ(client_->sceneChanges(), 1u);
  EXPECT_EQ(scene(), "vvalley");
  ASSERT_EQ(changes_.size(), 1u);
  EXPECT_EQ(changes_[0].from, (SceneIdentity{"marble_bricks", 0x10}));
  EXPECT_EQ(changes_[0].to, (SceneIdentity{"vvalley", 0x20}));
  EXPECT_EQ(changes_[0].server_instance, 5);
  EXPECT_FALSE(changes_[0].restart);
  server.hello();  // the next periodic hello repeats it
  pump();
  EXPECT_EQ(client_->sceneChanges(), 1u);
}

TEST_F(SceneChanges, TheSameNameWithAnotherTextureIsAChange) {
  FakeServer server(lcm_, 5, now_);
  server.hello();
  pump();
  server.switchScene(server.scene_name, server.texture_fingerprint + 1);  // the file was edited and loaded again
  pump();
  ASSERT_EQ(changes_.size(), 1u);
  EXPECT_EQ(changes_[0].from.name, changes_[0].to.name);
  EXPECT_NE(changes_[0].from.texture_fingerprint, changes_[0].to.texture_fingerprint);
}

TEST_F(SceneChanges, ARestartOnTheSameSceneIsNoChangeOnAnotherSceneIs) {
  auto first = std::make_unique<FakeServer>(lcm_, 5, now_);
  first->hello();
  pump();
  first.reset();
  FakeServer same(lcm_, 6, now_);  // hapticd restarted with the same --scene
  same.hello();
  pump();
  EXPECT_EQ(client_->serverInstance(), 6);
  EXPECT_EQ(client_->sceneChanges(), 0u);
  EXPECT_TRUE(changes_.empty());

  FakeServer other(lcm_, 7, now_);  // and again, on another scene
  other.scene_name = "pinball";
  other.hello();
  pump();
  EXPECT_EQ(client_->sceneChanges(), 1u);
  ASSERT_EQ(changes_.size(), 1u);
  EXPECT_TRUE(changes_[0].restart);
  EXPECT_EQ(changes_[0].server_instance, 7);
  EXPECT_EQ(scene(), "pinball");
}

TEST_F(SceneChanges, AnOlderHelloCannotSwitchBack) {
  FakeServer server(lcm_, 5, now_);
  server.hello();  // seq 1, "default"
  pump();
  server.switchScene("vvalley", 0x20);  // seq 2
  pump();
  thx_msgs::hello_t late{};  // hello 1 again, delivered late
  late.seq = 1;
  late.server_instance = 5;
  late.protocol_version = thx_msgs::hello_t::PROTOCOL_VERSION;
  late.scene_name = "default";
  late.texture_fingerprint = 0x1111;
  lcm_.publish(thx_msgs::kChannelHello, &late);
  pump();
  EXPECT_EQ(scene(), "vvalley");
  EXPECT_EQ(client_->sceneChanges(), 1u);
}

TEST_F(SceneChanges, TwoSwitchesBetweenPollsCountTwiceAndLeaveTheNewest) {
  FakeServer server(lcm_, 5, now_);
  server.hello();
  pump();
  const std::uint64_t seen = client_->sceneChanges();
  server.switchScene("vvalley", 0x20);
  server.switchScene("pinball", 0x30);
  pump();
  EXPECT_EQ(client_->sceneChanges() - seen, 2u);  // a poller rebuilds once, on the newest
  EXPECT_EQ(scene(), "pinball");
  ASSERT_EQ(changes_.size(), 2u);
  EXPECT_EQ(changes_[1].from.name, "vvalley");
}

}  // namespace test_scene_changes
