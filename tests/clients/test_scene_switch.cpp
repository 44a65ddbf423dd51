// A client switches hapticd's scene while it runs (server_command_t ACTION_LOAD_SCENE): the reply
// comes when the servo renders the new scene, the next hello names it with the fingerprint a
// client computes from its own copy, a broken scene is refused with the loader's file:line error
// and the old scene keeps running, and hapticd ends cleanly with a safe force. hapticd as a
// process over udpm (skipped without a multicast route); the client is raw LCM, as any
// language's would be.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <lcm/lcm-cpp.hpp>
#include <optional>

#include "scenes/scene_loader.hpp"
#include "scenes/scene_surface.hpp"
#include "server/session_log.hpp"
#include "tests/support/hapticd_harness.hpp"
#include "thx_msgs/protocol.hpp"

namespace test_scene_switch {

namespace {

using namespace thx;
using namespace thx::test;
namespace fs = std::filesystem;
using Cmd = thx_msgs::server_command_t;

struct Inbox {
  void onHello(const lcm::ReceiveBuffer* rbuf, const std::string&) {
    thx_msgs::hello_t h;
    if (thx_msgs::try_decode(rbuf->data, rbuf->data_size, h) > 0) hello = h;
  }
  void onReply(const lcm::ReceiveBuffer* rbuf, const std::string&) {
    thx_msgs::server_command_reply_t r;
    if (thx_msgs::try_decode(rbuf->data, rbuf->data_size, r) > 0 && r.client_id == "runner") reply = r;
  }
  std::optional<thx_msgs::hello_t> hello;
  std::optional<thx_msgs::server_command_reply_t> reply;
};

class SceneSwitch : public test::HapticdProcessTest {
 protected:
  bool waitFor(lcm::LCM& lcm, const std::function<bool()>& done, double timeout_s) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
    while (!done() && std::chrono::steady_clock::now() < end) lcm.handleTimeout(50);
    return done();
  }
  std::optional<thx_msgs::server_command_reply_t> loadScene(lcm::LCM& lcm, Inbox& inbox, const std::string& name) {
    Cmd c{};
    c.seq = ++seq_;
    c.client_id = "runner";
    c.action = Cmd::ACTION_LOAD_SCENE;
    c.argument = name;
    inbox.reply.reset();
    lcm.publish(thx_msgs::kChannelCommand, &c);
    waitFor(lcm, [&] { return inbox.reply && inbox.reply->request_seq == seq_; }, 60);
    return inbox.reply;
  }
  std::int64_t seq_ = 0;
};

TEST_F(SceneSwitch, AClientSwitchesTheSceneAndABrokenOneIsRefusedWhileTheOldOneRuns) {
  if (!udpmAvailable()) GTEST_SKIP() << "LCM udpm is not available here (" << url_ << "): no multicast route";
  // The server's scenes folder: the shipped V-valleys and a scene with an error on line 3.
  const fs::path scenes = dir_ / "scenes";
  fs::create_directories(scenes);
  fs::copy_file(fs::path(THX_SOURCE_DIR) / "scenes/vvalley.yaml", scenes / "vvalley.yaml");
  std::ofstream(scenes / "broken.yaml") << "version: 1\nname: broken\nsurface: [1, 2]\n";

  lcm::LCM lcm(url_);
  Inbox inbox;
  lcm.subscribe(thx_msgs::kChannelHello, &Inbox::onHello, &inbox);
  lcm.subscribe(thx_msgs::kChannelCommandReply, &Inbox::onReply, &inbox);
  const std::string record = (dir_ / "session.lcm").string();
  startServer({"--scene", "scenes/default.yaml", "--scenes-dir", scenes.string(), "--record", record});
  ASSERT_TRUE(waitFor(lcm, [&] { return inbox.hello.has_value(); }, 30)) << serverLog();
  EXPECT_EQ(inbox.hello->scene_name, "default");
  EXPECT_GE(inbox.hello->protocol_version, 3);  // scene switches since version 3
  const std::int64_t instance = inbox.hello->server_instance;

  const auto good = loadScene(lcm, inbox, "vvalley");
  ASSERT_TRUE(good) << "no reply within 60 s; hapticd said:\n" << serverLog();
  EXPECT_TRUE(good->accepted) << good->reason;
  EXPECT_GT(good->tick, 0);
  EXPECT_EQ(good->server_instance, instance);
  // The hello that follows names the new scene; the fingerprint is what a client computes from
  // its own copy of the file.
  ASSERT_TRUE(waitFor(lcm, [&] { return inbox.hello->scene_name == "vvalley"; }, 10)) << serverLog();
  const scene::SceneSurface mine = scene::buildSceneSurface(scene::loadScene((scenes / "vvalley.yaml").string()));
  EXPECT_EQ(static_cast<std::uint64_t>(inbox.hello->texture_fingerprint), mine.fingerprint);
  EXPECT_EQ(inbox.hello->server_instance, instance);  // the same server: no restart

  const auto bad = loadScene(lcm, inbox, "broken");
  ASSERT_TRUE(bad) << serverLog();
  EXPECT_FALSE(bad->accepted);
  EXPECT_EQ(bad->tick, -1);
  EXPECT_NE(bad->reason.find("broken.yaml:3:"), std::string::npos) << bad->reason;
  // The old scene keeps running: the next hellos still name it.
  const std::int64_t seq_after = inbox.hello->seq;
  ASSERT_TRUE(waitFor(lcm, [&] { return inbox.hello->seq > seq_after; }, 10)) << serverLog();
  EXPECT_EQ(inbox.hello->scene_name, "vvalley");

  EXPECT_EQ(stopServer(), 0) << serverLog();
  expectServoRanSafely();
  EXPECT_NE(serverLog().find("client runner switched the scene"), std::string::npos) << serverLog();

  // The recorded session says which scene each tick belongs to: a hello before the first tick
  // and one before the first tick on vvalley (the reply's tick), each with that tick's utime;
  // none for the refused switch.
  const std::vector<thx_msgs::contact_t> contacts = srv::loadSessionContacts(record);
  const std::vector<thx_msgs::hello_t> hellos = srv::loadSessionHellos(record);
  ASSERT_FALSE(contacts.empty());
  ASSERT_EQ(hellos.size(), 2u);
  EXPECT_EQ(hellos[0].scene_name, "default");
  EXPECT_EQ(hellos[0].utime, contacts.front().utime);
  EXPECT_EQ(hellos[1].scene_name, "vvalley");
  EXPECT_EQ(static_cast<std::uint64_t>(hellos[1].texture_fingerprint), mine.fingerprint);
  const auto first_on_vvalley = std::find_if(contacts.begin(), contacts.end(),
                                             [&](const thx_msgs::contact_t& c) { return c.tick == good->tick; });
  ASSERT_NE(first_on_vvalley, contacts.end());
  EXPECT_EQ(hellos[1].utime, first_on_vvalley->utime);
  // In the log the hello comes just before that tick's events.
  lcm::LogFile log(record, "r");
  bool hello_then_tick = false;
  for (int hellos_seen = 0; const lcm::LogEvent* e = log.readNextEvent();) {
    if (e->channel == thx_msgs::kChannelHello) ++hellos_seen;
    if (hellos_seen == 2 && e->channel == "THX_CONTACT") {
      thx_msgs::contact_t c;
      hello_then_tick = c.decode(e->data, 0, e->datalen) > 0 && c.tick == good->tick;
      break;
    }
  }
  EXPECT_TRUE(hello_then_tick);

  // audio-client renders the session's pen scrape in two stretches, the second on vvalley (found
  // in the scenes folder), the same bytes twice. A coarse slab without the pen keeps it fast.
  const auto render = [&](const std::string& wav) {
    return shellStatus(std::string("cd '") + THX_SOURCE_DIR + "' && '" + THX_AUDIO_CLIENT +
                       "' --scene scenes/default.yaml --scenes-dir '" + scenes.string() + "' --replay-log '" + record +
                       "' --wav '" + path(wav) + "' --slab-cells 2 --modes 8 --no-pen --tail 0.05 --cache-dir '" +
                       path("cache") + "' >'" + path(wav + ".out") + "' 2>&1");
  };
  ASSERT_EQ(render("a.wav"), 0) << slurp(path("a.wav.out"));
  EXPECT_NE(slurp(path("a.wav.out")).find("the pen's scrape in 2 stretches, scenes: default vvalley"), std::string::npos)
      << slurp(path("a.wav.out"));
  ASSERT_EQ(render("b.wav"), 0) << slurp(path("b.wav.out"));
  EXPECT_EQ(slurp(path("a.wav")), slurp(path("b.wav")));
}

// As a user runs it: hapticd, a physics-client on the same scene, and hapticctl switching the
// scene. The physics client follows (it loads the new scene from its own folder and says so);
// hapticctl prints the tick hapticd answered with, and a refusal with hapticd's reason. The
// physics client runs until it has followed the switch and is then stopped as a user stops it
// (SIGINT): a fixed --duration could end before a slow VM had started the two hapticctl runs.
TEST_F(SceneSwitch, HapticctlSwitchesTheSceneAndThePhysicsClientFollows) {
  if (!udpmAvailable()) GTEST_SKIP() << "LCM udpm is not available here (" << url_ << "): no multicast route";
  startServer({"--scene", "scenes/pen_pushes_ball.yaml"});
  const pid_t physics = spawn({THX_PHYSICS_CLIENT, "--scene", "scenes/pen_pushes_ball.yaml", "--lcm-url", url_,
                               "--connect-timeout", "60", "--json", path("pc.json")},
                              path("pc.out"), path("pc.err"));
  children_.push_back(physics);
  ASSERT_TRUE(waitUntil([&] { return slurp(path("pc.err")).find("connected") != std::string::npos; }, 60))
      << slurp(path("pc.err")) << serverLog();

  const int refused = shellStatus(std::string("'") + THX_HAPTICCTL + "' --lcm-url '" + url_ +
                                  "' --timeout 60 load-scene nosuch >'" + path("ctl1.out") + "' 2>'" +
                                  path("ctl1.err") + "'");
  EXPECT_EQ(refused, 1);
  EXPECT_NE(slurp(path("ctl1.err")).find("refused to load scene 'nosuch': scene 'nosuch' not found"),
            std::string::npos)
      << slurp(path("ctl1.err"));

  const int switched = shellStatus(std::string("'") + THX_HAPTICCTL + "' --lcm-url '" + url_ +
                                   "' --timeout 60 load-scene pinball >'" + path("ctl2.out") + "' 2>'" +
                                   path("ctl2.err") + "'");
  EXPECT_EQ(switched, 0) << slurp(path("ctl2.err"));
  EXPECT_NE(slurp(path("ctl2.out")).find("scene 'pinball' rendered from tick "), std::string::npos)
      << slurp(path("ctl2.out"));

  EXPECT_TRUE(waitUntil([&] { return slurp(path("pc.err")).find("switched to scene 'pinball'") != std::string::npos; }, 60))
      << slurp(path("pc.err"));
  kill(physics, SIGINT);
  EXPECT_EQ(reap(physics, 180), 0) << slurp(path("pc.err"));
  std::erase(children_, physics);
  const std::string err = slurp(path("pc.err"));
  EXPECT_NE(err.find("switched to scene 'pinball': following with scenes/pinball.yaml"), std::string::npos) << err;
  const std::string json = slurp(path("pc.json"));
  EXPECT_EQ(test::jsonField(json, "scene_name"), "pinball") << json;
  EXPECT_EQ(test::jsonNumber(json, "scene_switches"), 1) << json;
  EXPECT_EQ(stopServer(), 0) << serverLog();
  expectServoRanSafely();
}

}  // namespace

}  // namespace test_scene_switch
