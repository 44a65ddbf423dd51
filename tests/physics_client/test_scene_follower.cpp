// physics-client following hapticd's scene (clients/physics_client/scene_follower.hpp), in one
// process with no network: a switch to a scene of its folder rebuilds the simulation (the new
// scene's objects, its name, steps counted over the run); the current scene is no switch; a scene
// the folder lacks or that does not load stops with the scene, the folder and why; another texture
// under the same name is the start's mismatch error (thx_client checkScene). Deterministic.
#include <gtest/gtest.h>

#include "tests/support/error_text.hpp"
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "clients/physics_client/scene_follower.hpp"
#include "tests/physics_client/small_scenes.hpp"

namespace test_scene_follower {

namespace {

using namespace thx::physclient;
namespace fs = std::filesystem;

// Counts what the driver hands over.
struct CountingSink final : EventSink {
  int forces = 0, pose_reports = 0;
  void force(const PhysicsScene&, const PenForce&, std::int64_t) override { ++forces; }
  void poses(const PhysicsScene&, std::int64_t, const Eigen::Vector3d&) override { ++pose_reports; }
};

using thx::test::errorOf;

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

class Follower : public ::testing::Test {
 protected:
  void SetUp() override {
    static int n = 0;
    dir_ = fs::temp_directory_path() / ("thx_follower_" + std::to_string(::getpid()) + "_" + std::to_string(n++));
    alpha_ = thx::test::writeSmallScene(dir_, "alpha", "pen_pushes_ball_dimples");  // 1 ball
    beta_ = thx::test::writeSmallScene(dir_, "beta", "zigzag_street");             // 3 balls and a kerb
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  Options options() const { return parseOptions({"--scene", alpha_, "--quiet"}); }

  fs::path dir_;
  std::string alpha_, beta_;
};

}  // namespace

TEST_F(Follower, FollowsASwitchToASceneOfItsFolder) {
  SceneFollower sim(options());
  EXPECT_EQ(sim.scenesDir(), dir_.string());  // the --scene file's folder
  EXPECT_EQ(sim.identity(), thx::test::identityOf(alpha_));
  CountingSink sink;
  sim.start(sink);
  for (int k = 0; k < 10; ++k) sim.driver().step(std::nullopt);

  const thx::client::SceneIdentity beta = thx::test::identityOf(beta_);
  EXPECT_TRUE(sim.follow(beta, "hapticd@test"));
  EXPECT_EQ(sim.identity(), beta);
  EXPECT_EQ(sim.file(), (dir_ / "beta.yaml").string());
  EXPECT_EQ(sim.switches(), 1);
  EXPECT_EQ(sim.physics().scene().objects.size(), 4u);
  EXPECT_EQ(sim.physics().steps(), 0);  // a new simulation, from its scene's start
  EXPECT_DOUBLE_EQ(sim.rates().rate_hz, sim.physics().scene().rates.physics_hz);
  for (int k = 0; k < 5; ++k) sim.driver().step(std::nullopt);

  const RunSummary s = sim.summary();
  EXPECT_EQ(s.scene_name, "beta");
  EXPECT_EQ(s.scene_switches, 1);
  EXPECT_EQ(s.steps, 15);  // both scenes' steps
  ASSERT_EQ(s.objects.size(), 4u);  // the current scene's objects
  EXPECT_EQ(s.objects[0].name, "ball1");
  EXPECT_EQ(s.objects[3].name, "kerb");
  EXPECT_GT(sink.pose_reports, 0);  // the new driver hands over to the same sink
}

TEST_F(Follower, TheCurrentSceneIsNoSwitch) {
  SceneFollower sim(options());
  CountingSink sink;
  sim.start(sink);
  EXPECT_FALSE(sim.follow(sim.identity()));
  EXPECT_EQ(sim.switches(), 0);
  EXPECT_EQ(sim.summary().scene_name, "alpha");
  EXPECT_EQ(sim.summary().scene_switches, 0);
}

TEST_F(Follower, ASceneTheFolderLacksStopsNamingTheSceneAndTheFolder) {
  SceneFollower sim(options());
  CountingSink sink;
  sim.start(sink);
  const std::string e = errorOf([&] { sim.follow({"gamma", 0x1}, "hapticd@lab1"); });
  EXPECT_TRUE(has(e, "hapticd@lab1 switched to scene 'gamma', which this client cannot load from its scenes folder '" +
                         dir_.string() + "'"))
      << e;
  EXPECT_TRUE(has(e, "scenes in '" + dir_.string() + "': alpha, beta")) << e;  // what the folder does hold
  EXPECT_TRUE(has(e, "so the two folders differ")) << e;
  EXPECT_EQ(sim.identity().name, "alpha");  // the old simulation stays
  sim.driver().step(std::nullopt);
  EXPECT_EQ(sim.summary().steps, 1);
}

TEST_F(Follower, ASceneThatDoesNotLoadStopsWithTheLoadersError) {
  std::ofstream(dir_ / "broken.yaml") << "version: 1\nsurface: [\n";
  SceneFollower sim(options());
  const std::string e = errorOf([&] { sim.follow({"broken", 0x1}); });
  EXPECT_TRUE(has(e, "hapticd switched to scene 'broken', which this client cannot load")) << e;
  EXPECT_TRUE(has(e, "broken.yaml:")) << e;  // the loader's file:line
  EXPECT_EQ(sim.identity().name, "alpha");
}

TEST_F(Follower, AnotherTextureUnderTheSameNameIsTheStartsMismatchError) {
  SceneFollower sim(options());
  thx::client::SceneIdentity server = thx::test::identityOf(beta_);
  const thx::client::SceneIdentity mine = server;
  server.texture_fingerprint ^= 1;  // hapticd's beta.yaml is another version
  const std::string e = errorOf([&] { sim.follow(server, "hapticd@lab1"); });
  EXPECT_EQ(e, thx::client::checkScene(server, mine, false, "hapticd@lab1").message);
  EXPECT_TRUE(has(e, "texture mismatch: hapticd@lab1 runs scene 'beta'")) << e;
  EXPECT_EQ(sim.identity().name, "alpha");
  EXPECT_EQ(sim.switches(), 0);
}

TEST(RunSummaryOverScenes, CountsAddMaximaStayTheMeanIsWeighted) {
  RunSummary a, b;
  a.steps = 100, a.sim_time_s = 0.1, a.pen_contact_steps = 10, a.mean_force_in_contact_n = 1.0, a.max_force_sent_n = 2.0;
  a.impacts = 3, a.pose_reports = 6, a.scene_name = "alpha";
  b.steps = 50, b.sim_time_s = 0.05, b.pen_contact_steps = 30, b.mean_force_in_contact_n = 0.5, b.max_force_sent_n = 1.0;
  b.impacts = 1, b.pose_reports = 3, b.scene_name = "beta";
  const RunSummary s = continuedRun(a, b);
  EXPECT_EQ(s.steps, 150);
  EXPECT_DOUBLE_EQ(s.sim_time_s, 0.15);
  EXPECT_EQ(s.pen_contact_steps, 40);
  EXPECT_DOUBLE_EQ(s.mean_force_in_contact_n, (10 * 1.0 + 30 * 0.5) / 40);
  EXPECT_DOUBLE_EQ(s.max_force_sent_n, 2.0);
  EXPECT_EQ(s.impacts, 4);
  EXPECT_EQ(s.pose_reports, 9);
  EXPECT_EQ(s.scene_name, "beta");
}

}  // namespace test_scene_follower
