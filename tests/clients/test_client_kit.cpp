// The client kit (clients/client_lib): ClientApp's LCM opening, waiting for the server's hello,
// the paced loop and the stop signal; typed Subscriber<M> for the broadcast channels with its
// error callback; Client's error callback. In one process over memq:// (LCM delivers what an
// instance publishes to its own subscribers): no network, outcomes independent of timing.
#include <gtest/gtest.h>

#include "tests/support/error_text.hpp"

#include <csignal>
#include <lcm/lcm-cpp.hpp>
#include <thx_msgs/protocol.hpp>
#include <vector>

#include "thx_client/app.hpp"
#include "thx_client/stop_signal.hpp"
#include "thx_client/scene_check.hpp"
#include "thx_client/subscriber.hpp"

namespace test_client_kit {

using namespace thx::client;

namespace {

thx_msgs::physics_poses_t poses(std::int64_t seq) {
  thx_msgs::physics_poses_t m{};
  m.seq = seq;
  m.num_bodies = 0;
  return m;
}

void publishGarbage(lcm::LCM& lcm, const std::string& channel) {
  const std::uint8_t junk[5] = {1, 2, 3, 4, 5};
  lcm.publish(channel, junk, sizeof junk);
}

using thx::test::errorOf;

class ClientKit : public ::testing::Test {
 protected:
  void SetUp() override { clearStopRequest(); }
  void TearDown() override { clearStopRequest(); }
};

}  // namespace

TEST_F(ClientKit, SubscriberDeliversTypedMessagesAndKeepsTheLatest) {
  lcm::LCM lcm("memq://");
  ASSERT_TRUE(lcm.good());
  PhysicsPosesSubscriber sub(lcm);
  EXPECT_EQ(sub.channel(), thx_msgs::kChannelPhysicsPoses);
  std::vector<std::int64_t> seen;
  sub.onMessage([&](const thx_msgs::physics_poses_t& m, std::int64_t receipt_ns) {
    EXPECT_GT(receipt_ns, 0);
    seen.push_back(m.seq);
  });
  EXPECT_FALSE(sub.latest());
  for (std::int64_t k = 1; k <= 3; ++k) {
    const auto m = poses(k);
    lcm.publish(thx_msgs::kChannelPhysicsPoses, &m);
  }
  while (lcm.handleTimeout(0) > 0) {
  }
  EXPECT_EQ(seen, (std::vector<std::int64_t>{1, 2, 3}));
  ASSERT_TRUE(sub.latest());
  EXPECT_EQ(sub.latest()->seq, 3);
  EXPECT_EQ(sub.received(), 3u);
  EXPECT_EQ(sub.undecodable(), 0u);
}

TEST_F(ClientKit, SubscriberReportsBytesThatDoNotDecodeAndKeepsGoing) {
  lcm::LCM lcm("memq://");
  PhysicsImpactSubscriber sub(lcm);
  std::vector<std::string> errors;
  sub.onError([&](const DecodeError& e) { errors.push_back(e.message()); });
  publishGarbage(lcm, thx_msgs::kChannelPhysicsImpact);
  const auto poses_on_the_wrong_channel = poses(1);  // another type's fingerprint
  lcm.publish(thx_msgs::kChannelPhysicsImpact, &poses_on_the_wrong_channel);
  thx_msgs::physics_impact_t good{};
  good.seq = 7;
  lcm.publish(thx_msgs::kChannelPhysicsImpact, &good);
  while (lcm.handleTimeout(0) > 0) {
  }
  ASSERT_EQ(errors.size(), 2u);
  EXPECT_EQ(errors[0], "THX_PHYSICS_IMPACT: 5 bytes that do not decode as physics_impact_t");
  EXPECT_EQ(sub.undecodable(), 2u);
  ASSERT_TRUE(sub.latest());
  EXPECT_EQ(sub.latest()->seq, 7);
}

TEST_F(ClientKit, ClientReportsUndecodableHellos) {
  ClientApp app("kit", "memq://", 1.0);
  std::vector<DecodeError> errors;
  app.client().onError([&](const DecodeError& e) { errors.push_back(e); });
  publishGarbage(app.lcm(), thx_msgs::kChannelHello);
  app.client().poll(0);
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors[0].channel, thx_msgs::kChannelHello);
  EXPECT_EQ(errors[0].expected_type, "hello_t");
  EXPECT_EQ(app.client().counters().undecodable, 1u);
}

TEST_F(ClientKit, AnUnusableLcmUrlIsAnErrorThatNamesItAndTheFix) {
  EXPECT_EQ(errorOf([] { openLcm("udpm://10.1.2.3:7667?ttl=0"); }),
            "LCM is not available at 'udpm://10.1.2.3:7667?ttl=0' (no multicast route? try `ip route add "
            "224.0.0.0/4 dev lo` as root, or --lcm-url)");
  EXPECT_EQ(errorOf([] { ClientApp app("kit", "nonsense://x"); }),
            "LCM is not available at 'nonsense://x' (check --lcm-url)");
}

TEST_F(ClientKit, WaitForServerReturnsTheHello) {
  ClientApp app("kit", "memq://", 5.0);
  thx_msgs::hello_t h{};
  h.seq = 1;
  h.server_instance = 42;
  h.server_name = "hapticd@test";
  app.lcm().publish(thx_msgs::kChannelHello, &h);
  const auto got = app.waitForServer();
  ASSERT_TRUE(got);
  EXPECT_EQ(got->server_instance, 42);
  EXPECT_EQ(app.client().serverInstance(), 42);
}

TEST_F(ClientKit, NoServerIsAnErrorNamingTheUrl) {
  ClientApp app("kit", "memq://", 0.05);
  EXPECT_EQ(errorOf([&] { app.waitForServer(); }),
            "no hello from hapticd within 0.05 s on memq:// (is hapticd running with LCM on this URL?)");
}

TEST_F(ClientKit, PacedLoopRunsItsStepsAndStopsWhenTold) {
  ClientApp app("kit", "memq://");
  int calls = 0;
  std::int64_t last_tick = -1;
  const LoopStats five = app.runPaced(1000.0, [&](const thx::rt::TickTiming& t) {
    EXPECT_GT(t.tick, last_tick);  // grid ticks only go forward (skipped ones count)
    last_tick = t.tick;
    ++calls;
    return true;
  }, 5);
  EXPECT_EQ(five.steps, 5);
  EXPECT_EQ(calls, 5);
  const LoopStats one = app.runPaced(1000.0, [](const thx::rt::TickTiming&) { return false; });
  EXPECT_EQ(one.steps, 1);
}

TEST_F(ClientKit, SigtermStopsTheLoopsAndTheWaits) {
  ClientApp app("kit", "memq://", 30.0);  // installs the handlers
  std::raise(SIGTERM);
  EXPECT_TRUE(app.stopRequested());
  EXPECT_EQ(app.runPaced(1000.0, [](const thx::rt::TickTiming&) { return true; }).steps, 0);
  EXPECT_FALSE(app.waitForServer());  // returns at once instead of waiting 30 s
  EXPECT_FALSE(app.pollUntil([] { return false; }, 30.0));
}

TEST_F(ClientKit, WaitForServerStopsAClientOnAnotherSceneUnlessToldToDiffer) {
  thx_msgs::hello_t h{};
  h.seq = 1;
  h.server_instance = 7;
  h.scene_name = "vvalley";
  h.texture_fingerprint = 0x1234;
  for (const bool allow : {false, true}) {
    AppOptions o;
    o.client_id = "kit";
    o.lcm_url = "memq://";
    o.scene = SceneIdentity{"marble_bricks", 0x5678};
    o.allow_different_scene = allow;
    ClientApp app(o);
    app.lcm().publish(thx_msgs::kChannelHello, &h);
    if (!allow) {
      const std::string e = errorOf([&] { app.waitForServer(); });
      EXPECT_NE(e.find("vvalley"), std::string::npos) << e;
      EXPECT_NE(e.find("marble_bricks"), std::string::npos) << e;
      EXPECT_NE(e.find("--allow-different-scene"), std::string::npos) << e;
    } else {
      EXPECT_TRUE(app.waitForServer());  // a warning on stderr, and on it goes
    }
  }
}

}  // namespace test_client_kit
