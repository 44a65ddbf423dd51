// physics-client (the binary) following a scene switch online, against the fake hapticd of
// tests/support in this test's process on a udpm port of the test's own (ttl=0; skipped without
// a multicast route). The fake serves the pen (above the plane: no contact force), hellos, and
// then announces another scene, as hapticd does after a client's ACTION_LOAD_SCENE. Checked, each
// by waiting for what physics-client publishes (never by counting on the scheduler): it steps
// the first scene (poses of 1 body), lets go of the pen when the switch comes (a zero
// client_force_t before any pose of the new scene), then publishes the new scene's 4 bodies, says
// so on stderr, and reports the switch in its --json. A scene its folder lacks stops it (exit 1)
// naming the scene and the folder; with --allow-different-scene it keeps its scene and says so once.
#include <signal.h>
#include <sys/wait.h>

#include <lcm/lcm-cpp.hpp>
#include <string>
#include <thx_msgs/protocol.hpp>

#include "rt/clock.hpp"
#include "tests/physics_client/small_scenes.hpp"
#include "tests/support/fake_server.hpp"
#include "tests/support/hapticd_harness.hpp"

namespace test_follow_online {

namespace {

using namespace thx::test;

// What physics-client publishes, as the test process hears it.
struct Heard {
  std::int64_t poses_1_body = 0, poses_4_bodies = 0;
  std::int64_t zero_forces = 0;                // client_force_t with f = 0 (a release)
  std::int64_t zero_forces_before_4_bodies = -1;  // zero_forces when the first 4-body pose came
  void onPoses(const lcm::ReceiveBuffer* rbuf, const std::string&) {
    thx_msgs::physics_poses_t m;
    if (thx_msgs::try_decode(rbuf->data, rbuf->data_size, m) < 0) return;
    if (m.num_bodies == 1) ++poses_1_body;
    if (m.num_bodies != 4) return;
    if (poses_4_bodies++ == 0) zero_forces_before_4_bodies = zero_forces;
  }
  void onForce(const lcm::ReceiveBuffer* rbuf, const std::string&) {
    thx_msgs::client_force_t m;
    if (thx_msgs::try_decode(rbuf->data, rbuf->data_size, m) < 0) return;
    if (m.f_world[0] == 0 && m.f_world[1] == 0 && m.f_world[2] == 0) ++zero_forces;
  }
};

// Whether the child has ended, leaving it to be reaped (reap() reads its status).
bool ended(pid_t pid) {
  siginfo_t info{};
  return waitid(P_PID, id_t(pid), &info, WEXITED | WNOHANG | WNOWAIT) == 0 && info.si_pid == pid;
}

class PhysicsClientFollows : public HapticdProcessTest {
 protected:
  void SetUp() override {
    HapticdProcessTest::SetUp();
    if (!udpmAvailable()) return;
    lcm_ = std::make_unique<lcm::LCM>(url_);
    now_ = thx::rt::monotonicNowNs();
    server_fake_ = std::make_unique<FakeServer>(*lcm_, 99, now_);
    alpha_ = writeSmallScene(dir_ / "scenes", "alpha", "pen_pushes_ball_dimples");  // 1 ball
    beta_ = writeSmallScene(dir_ / "scenes", "beta", "zigzag_street");             // 3 balls and a kerb
    const thx::client::SceneIdentity a = identityOf(alpha_);
    server_fake_->scene_name = a.name;
    server_fake_->texture_fingerprint = a.texture_fingerprint;
    server_fake_->pen_world[2] = 0.1;  // 10 cm above both planes: the pen touches nothing
    lcm_->subscribe(thx_msgs::kChannelPhysicsPoses, &Heard::onPoses, &heard_);
    lcm_->subscribe(thx_msgs::kChannelClientForce, &Heard::onForce, &heard_);
  }
  void TearDown() override {
    server_fake_.reset();
    lcm_.reset();
    HapticdProcessTest::TearDown();
  }

  pid_t startPhysicsClient(const std::vector<std::string>& extra) {
    std::vector<std::string> a = {THX_PHYSICS_CLIENT, "--scene", alpha_, "--lcm-url", url_, "--client-id", "follow",
                                  "--connect-timeout", "30", "--json", path("pc.json")};
    a.insert(a.end(), extra.begin(), extra.end());
    const pid_t p = spawn(a, path("pc.out"), path("pc.err"));
    children_.push_back(p);
    return p;
  }
  int finish(pid_t p, bool stop) {
    if (stop) kill(p, SIGTERM);
    const int rc = reap(p, 30);
    std::erase(children_, p);
    return rc;
  }
  std::string err() const { return slurp(path("pc.err")); }

  // Serves as hapticd would (a hello every 0.25 s, a servo tick per elapsed millisecond) until
  // done() holds or timeout_s passes, or the client exits when `client` is given.
  bool serveUntil(const std::function<bool()>& done, double timeout_s, pid_t client = -1) {
    const std::int64_t give_up = thx::rt::monotonicNowNs() + std::int64_t(timeout_s * 1e9);
    while (!done()) {
      now_ = thx::rt::monotonicNowNs();
      if (now_ > give_up) return false;
      if (client > 0 && ended(client)) {
        // What the client sent just before it exited (its zero force letting go of the pen) may
        // still wait in the socket: read it before deciding (a clean clone's make test once
        // missed it, heard_.zero_forces 0).
        while (lcm_->handleTimeout(50) > 0) {
        }
        return done();
      }
      if (now_ >= next_hello_) {
        server_fake_->hello();
        next_hello_ = now_ + 250'000'000;
      }
      if (first_tick_ns_ == 0) first_tick_ns_ = now_;
      const std::int64_t due = (now_ - first_tick_ns_) / 1'000'000 + 1;
      if (due > ticks_) server_fake_->ticks(ticks_, due - ticks_), ticks_ = due;
      lcm_->handleTimeout(1);
    }
    return true;
  }

  std::unique_ptr<lcm::LCM> lcm_;
  std::int64_t now_ = 0, next_hello_ = 0, first_tick_ns_ = 0, ticks_ = 0;
  std::unique_ptr<FakeServer> server_fake_;
  Heard heard_;
  std::string alpha_, beta_;
};

}  // namespace

TEST_F(PhysicsClientFollows, ASwitchAnnouncedInTheHelloIsFollowed) {
  if (!lcm_) GTEST_SKIP() << "LCM udpm is not available here (" << url_ << "): no multicast route";
  const pid_t pc = startPhysicsClient({});
  ASSERT_TRUE(serveUntil([&] { return heard_.poses_1_body > 0; }, 60, pc)) << err();  // stepping alpha
  EXPECT_EQ(heard_.zero_forces, 0);  // nothing touched, nothing sent yet

  const thx::client::SceneIdentity b = identityOf(beta_);
  server_fake_->switchScene(b.name, b.texture_fingerprint);  // another client loaded beta
  ASSERT_TRUE(serveUntil([&] { return heard_.poses_4_bodies > 0; }, 60, pc)) << err();
  EXPECT_GE(heard_.zero_forces_before_4_bodies, 1);  // it let go of the pen before the new scene ran
  EXPECT_EQ(finish(pc, /*stop=*/true), 0) << err();

  const std::string e = err(), json = slurp(path("pc.json"));
  SCOPED_TRACE("physics-client stderr: " + e + "\n--json: " + json);
  EXPECT_NE(e.find("physics-client: fake switched to scene 'beta': following with " + path("scenes/beta.yaml") +
                   " (4 objects"),
            std::string::npos);
  EXPECT_EQ(jsonField(json, "scene_name"), "beta");
  EXPECT_EQ(jsonNumber(json, "scene_switches"), 1);
}

TEST_F(PhysicsClientFollows, ASceneItsFolderLacksStopsItNamingTheSceneAndTheFolder) {
  if (!lcm_) GTEST_SKIP() << "LCM udpm is not available here (" << url_ << "): no multicast route";
  const pid_t pc = startPhysicsClient({"--quiet"});
  ASSERT_TRUE(serveUntil([&] { return heard_.poses_1_body > 0; }, 60, pc)) << err();
  server_fake_->switchScene("gamma", 0x1234);  // the server's folder has it, this client's has not
  serveUntil([] { return false; }, 30, pc);    // until it exits
  EXPECT_EQ(finish(pc, /*stop=*/false), 1) << err();
  const std::string e = err();
  EXPECT_NE(e.find("physics-client: fake switched to scene 'gamma', which this client cannot load from its scenes "
                   "folder '" + path("scenes") + "'"),
            std::string::npos)
      << e;
  EXPECT_NE(e.find("the two folders differ"), std::string::npos) << e;
  EXPECT_GE(heard_.zero_forces, 1);  // the pen was let go first
}

TEST_F(PhysicsClientFollows, AllowDifferentSceneKeepsItsOwnAndSaysSoOnce) {
  if (!lcm_) GTEST_SKIP() << "LCM udpm is not available here (" << url_ << "): no multicast route";
  const pid_t pc = startPhysicsClient({"--allow-different-scene"});
  ASSERT_TRUE(serveUntil([&] { return heard_.poses_1_body > 0; }, 60, pc)) << err();
  const thx::client::SceneIdentity b = identityOf(beta_);
  server_fake_->switchScene(b.name, b.texture_fingerprint);
  ASSERT_TRUE(serveUntil([&] { return err().find("keeping scene 'alpha'") != std::string::npos; }, 60, pc)) << err();
  server_fake_->switchScene("gamma", 0x1234);  // a second switch: no second line, no stop
  const std::int64_t poses_before = heard_.poses_1_body;
  ASSERT_TRUE(serveUntil([&] { return heard_.poses_1_body > poses_before + 10; }, 60, pc)) << err();  // still stepping alpha
  EXPECT_EQ(finish(pc, /*stop=*/true), 0) << err();

  const std::string e = err(), json = slurp(path("pc.json"));
  EXPECT_EQ(e.find("keeping scene"), e.rfind("keeping scene")) << e;  // once
  EXPECT_EQ(heard_.poses_4_bodies, 0);
  EXPECT_EQ(jsonField(json, "scene_name"), "alpha");
  EXPECT_EQ(jsonNumber(json, "scene_switches"), 0);
}

}  // namespace test_follow_online
