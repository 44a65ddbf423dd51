// Server commands through the kit (thx_client/commands.hpp, Client::sendCommand, ClientApp::command,
// resetFaults, loadScene) against the fake hapticd of tests/support over memq://: the round trip
// (seq, reply, tick), a refusal with the server's reason, no reply (a timeout naming the command),
// arguments refused before sending, a server too old for the command, replies that are not ours.
// One process, no network; the only clock is the timeout's, and no assertion depends on timing.
#include <gtest/gtest.h>

#include "tests/support/error_text.hpp"

#include <lcm/lcm-cpp.hpp>
#include <string>
#include <thx_msgs/protocol.hpp>
#include <vector>

#include "tests/support/fake_server.hpp"
#include "thx_client/app.hpp"
#include "thx_client/commands.hpp"
#include "thx_client/stop_signal.hpp"

namespace test_commands {

using namespace thx;
using client::ClientApp;
using client::CommandRefused;
using test::FakeServer;
using Cmd = thx_msgs::server_command_t;

namespace {

using thx::test::errorOf;

class Commands : public ::testing::Test {
 protected:
  void SetUp() override {
    client::clearStopRequest();
    server_.hello();
    ASSERT_TRUE(app_.waitForServer());
  }
  void TearDown() override { client::clearStopRequest(); }

  std::int64_t now_ = 0;  // the fake's clock (subscriptions only; unused here)
  ClientApp app_{"kit", "memq://", 5.0};
  FakeServer server_{app_.lcm(), 77, now_};
};

}  // namespace

TEST_F(Commands, ClientSendsACommandAndKeepsItsReply) {
  client::Client& c = app_.client();
  std::vector<std::int64_t> callback_seqs;
  c.onCommandReply([&](const thx_msgs::server_command_reply_t& r) { callback_seqs.push_back(r.request_seq); });
  const std::int64_t first = c.sendCommand(Cmd::ACTION_RESET_FAULTS);
  const std::int64_t second = c.sendCommand(Cmd::ACTION_RESET_FAULTS, "");
  EXPECT_EQ(first, 1);  // per client: 1, 2, ... (docs/messages.md §5.10)
  EXPECT_EQ(second, 2);
  EXPECT_FALSE(c.takeCommandReply(first));  // nothing handled yet
  ASSERT_TRUE(app_.pollUntil([&] { return callback_seqs.size() == 2; }, 5.0));
  EXPECT_EQ(callback_seqs, (std::vector<std::int64_t>{1, 2}));

  ASSERT_EQ(server_.commands.size(), 2u);
  EXPECT_EQ(server_.commands[0].client_id, "kit");
  EXPECT_EQ(server_.commands[0].action, Cmd::ACTION_RESET_FAULTS);
  EXPECT_EQ(server_.commands[0].argument, "");
  EXPECT_EQ(server_.commands[1].seq, 2);

  const auto r = c.takeCommandReply(second);
  ASSERT_TRUE(r);
  EXPECT_TRUE(r->accepted);
  EXPECT_EQ(r->request_seq, 2);
  EXPECT_EQ(r->tick, 1234);
  EXPECT_EQ(r->server_instance, 77);
  EXPECT_FALSE(c.takeCommandReply(second));  // handed over once
  EXPECT_TRUE(c.takeCommandReply(first));
  EXPECT_EQ(c.counters().commands_sent, 2u);
  EXPECT_EQ(c.counters().command_replies, 2u);
}

TEST_F(Commands, ResetFaultsReturnsTheAcceptedReply) {
  server_.command_tick = 4321;
  const auto r = app_.resetFaults();
  ASSERT_TRUE(r);
  EXPECT_TRUE(r->accepted);
  EXPECT_EQ(r->action, Cmd::ACTION_RESET_FAULTS);
  EXPECT_EQ(r->tick, 4321);  // the first servo tick with the latch cleared
}

TEST_F(Commands, LoadSceneSwitchesTheServerAndTheClientSeesIt) {
  server_.scenes["vvalley"] = 0xabcd;
  ASSERT_EQ(app_.client().sceneChanges(), 0u);
  const auto r = app_.loadScene("vvalley");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->action, Cmd::ACTION_LOAD_SCENE);
  ASSERT_EQ(server_.commands.size(), 1u);
  EXPECT_EQ(server_.commands[0].argument, "vvalley");
  // The fake announced the new scene right after its reply, as hapticd does.
  ASSERT_TRUE(app_.pollUntil([&] { return app_.client().sceneChanges() == 1; }, 5.0));
  ASSERT_TRUE(app_.client().serverScene());
  EXPECT_EQ(app_.client().serverScene()->name, "vvalley");
  EXPECT_EQ(app_.client().serverScene()->texture_fingerprint, 0xabcdu);
}

TEST_F(Commands, ARefusalIsAnErrorWithTheServersReason) {
  // The loader's "file:line: ..." comes back as the reason.
  server_.command_answer = FakeServer::CommandAnswer::Refuse;
  server_.refusal = "scenes/broken.yaml:3:5: surface.size: expected two numbers > 0";
  try {
    app_.loadScene("broken");
    FAIL() << "no CommandRefused";
  } catch (const CommandRefused& e) {
    EXPECT_STREQ(e.what(),
                 "fake refused to load scene 'broken': scenes/broken.yaml:3:5: surface.size: expected two numbers > 0");
    EXPECT_FALSE(e.reply().accepted);
    EXPECT_EQ(e.reply().tick, -1);
    EXPECT_EQ(e.kind(), thx::Error::Kind::Config);
  }
  // A name the fake has no file for, refused as hapticd's loader would.
  server_.command_answer = FakeServer::CommandAnswer::Accept;
  EXPECT_EQ(errorOf([&] { app_.loadScene("nowhere"); }),
            "fake refused to load scene 'nowhere': scene 'nowhere' not found: no file scenes/nowhere.yaml");
  EXPECT_EQ(app_.client().sceneChanges(), 0u);  // nothing changed
}

TEST_F(Commands, NoReplyIsATimeoutNamingTheCommand) {
  server_.command_answer = FakeServer::CommandAnswer::Ignore;
  EXPECT_EQ(errorOf([&] { app_.resetFaults(0.05); }),
            "no reply from fake to 'reset faults' within 0.05 s on memq:// (is hapticd running? the command may "
            "still take effect)");
  EXPECT_EQ(server_.commands.size(), 1u);  // sent once, never resent
}

TEST_F(Commands, ArgumentsThatCannotGoOutAreRefusedBeforeSending) {
  for (const std::string bad : {"../etc/passwd", "", ".hidden", "a b", "scenes/x"}) {
    const std::string e = errorOf([&] { app_.loadScene(bad); });
    EXPECT_NE(e.find("invalid scene name '" + bad + "'"), std::string::npos) << e;
  }
  EXPECT_THROW(app_.client().sendCommand(Cmd::ACTION_LOAD_SCENE, "../x"), thx::Error);
  EXPECT_THROW(app_.client().sendCommand(Cmd::ACTION_RESET_FAULTS, std::string(300, 'x')), thx::Error);
  EXPECT_NE(errorOf([&] { app_.command(Cmd::ACTION_RESET_FAULTS, std::string(300, 'x'), 1.0); })
                .find("a command argument of 300 characters: expected fewer than 200"),
            std::string::npos);
  app_.client().poll(0);
  EXPECT_TRUE(server_.commands.empty());
}

TEST_F(Commands, AServerTooOldForTheCommandIsToldBeforeSending) {
  thx_msgs::hello_t old{};
  old.seq = 2;
  old.server_instance = 77;
  old.protocol_version = 2;  // answers resets, knows no scene loading
  old.server_name = "hapticd@old";
  app_.lcm().publish(thx_msgs::kChannelHello, &old);
  app_.client().poll(0);
  EXPECT_EQ(errorOf([&] { app_.loadScene("vvalley"); }),
            "cannot send 'load scene 'vvalley'': hapticd@old speaks protocol version 2, this command needs 3 (a newer "
            "hapticd)");
  EXPECT_TRUE(app_.resetFaults());
  EXPECT_EQ(server_.commands.size(), 1u);
}

TEST_F(Commands, OnlyRepliesToItsOwnWaitingCommandsCount) {
  client::Client& c = app_.client();
  server_.command_answer = FakeServer::CommandAnswer::Ignore;
  const std::int64_t seq = c.sendCommand(Cmd::ACTION_RESET_FAULTS);
  thx_msgs::server_command_reply_t r{};
  r.server_instance = 77;
  r.request_seq = seq;
  r.client_id = "other";  // another client's answer with the same seq
  r.accepted = true;
  app_.lcm().publish(thx_msgs::kChannelCommandReply, &r);
  r.client_id = "kit";
  r.request_seq = seq + 5;  // a command this client never sent (another process with our id)
  app_.lcm().publish(thx_msgs::kChannelCommandReply, &r);
  std::vector<client::DecodeError> errors;
  c.onError([&](const client::DecodeError& e) { errors.push_back(e); });
  const std::uint8_t junk[3] = {1, 2, 3};
  app_.lcm().publish(thx_msgs::kChannelCommandReply, junk, sizeof junk);
  for (int k = 0; k < 4; ++k) c.poll(0);
  EXPECT_FALSE(c.takeCommandReply(seq));
  EXPECT_FALSE(c.takeCommandReply(seq + 5));
  EXPECT_EQ(c.counters().command_replies, 0u);
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors[0].message(), "THX_COMMAND_REPLY: 3 bytes that do not decode as server_command_reply_t");

  r.request_seq = seq;  // ours at last
  app_.lcm().publish(thx_msgs::kChannelCommandReply, &r);
  r.accepted = false;  // a second answer to the same command is not taken
  app_.lcm().publish(thx_msgs::kChannelCommandReply, &r);
  for (int k = 0; k < 4; ++k) c.poll(0);
  const auto got = c.takeCommandReply(seq);
  ASSERT_TRUE(got);
  EXPECT_TRUE(got->accepted);
  EXPECT_EQ(c.counters().command_replies, 1u);
}

TEST_F(Commands, DescribeCommandNamesEachAction) {
  EXPECT_EQ(client::describeCommand(Cmd::ACTION_RESET_FAULTS, ""), "reset faults");
  EXPECT_EQ(client::describeCommand(Cmd::ACTION_LOAD_SCENE, "vvalley"), "load scene 'vvalley'");
  EXPECT_EQ(client::describeCommand(9, "x"), "action 9 ('x')");
  EXPECT_EQ(client::protocolVersionFor(Cmd::ACTION_LOAD_SCENE), 3);
  EXPECT_EQ(client::protocolVersionFor(9), 0);  // unknown: the server decides
}

}  // namespace test_commands
