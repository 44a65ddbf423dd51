// visual-client --live (issue 15): a frame is drawn only when the pen or a body moved (sameView on
// the messages' values); the proxy is read from device_state_t as hapticd fills it; without a
// server the client draws the scene at rest, the same picture as --screenshot.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "clients/visual/live_view.hpp"
#include "tests/support/port_block.hpp"

namespace thx::visual::test_live {
namespace {

namespace fs = std::filesystem;
using D = thx_msgs::device_state_t;

D stateAt(double x, bool held) {
  D s{};
  s.p_world[0] = x;
  s.p_world[2] = -0.001;
  s.proxy_world[0] = x;
  if (held) s.flags = std::int32_t{D::FLAG_PROXY_HELD} | D::FLAG_IN_CONTACT;
  return s;
}

thx_msgs::physics_poses_t posesAt(double x) {
  thx_msgs::physics_poses_t m{};
  m.num_bodies = 1;
  m.p_world[0][0] = x;
  m.q_world[0][0] = 1.0;
  return m;
}

TEST(VisualLive, AFrameOnlyWhenSomethingMoved) {
  const LiveView nothing = liveViewOf(std::nullopt, std::nullopt);
  EXPECT_FALSE(nothing.pen.has_value());
  EXPECT_TRUE(nothing.bodies.empty());
  EXPECT_TRUE(sameView(nothing, liveViewOf(std::nullopt, std::nullopt)));

  const LiveView a = liveViewOf(stateAt(0.01, true), posesAt(0.03));
  D later = stateAt(0.01, true);
  later.tick = 99;  // another tick, the same pen: no new frame
  later.utime = 99000;
  EXPECT_TRUE(sameView(a, liveViewOf(later, posesAt(0.03))));
  EXPECT_FALSE(sameView(a, nothing));
  EXPECT_FALSE(sameView(a, liveViewOf(stateAt(0.0101, true), posesAt(0.03))));  // the tip moved
  EXPECT_FALSE(sameView(a, liveViewOf(stateAt(0.01, false), posesAt(0.03))));   // the proxy let go
  EXPECT_FALSE(sameView(a, liveViewOf(stateAt(0.01, true), posesAt(0.0301))));  // a body moved
  EXPECT_FALSE(sameView(a, liveViewOf(stateAt(0.01, true), std::nullopt)));     // the poses went away
}

TEST(VisualLive, TheProxyAsPublished) {
  D s = stateAt(0.01, true);
  s.proxy_world[2] = 0.0;  // on the plane, the tip 1 mm below
  const PenView held = penViewOf(s);
  EXPECT_TRUE(held.proxy_held);
  EXPECT_EQ(held.proxy_world, Eigen::Vector3d(0.01, 0.0, 0.0));
  EXPECT_EQ(held.tip_world, Eigen::Vector3d(0.01, 0.0, -0.001));
  s.flags = 0;  // not held: the proxy is the tip, whatever the field holds
  EXPECT_EQ(penViewOf(s).proxy_world, penViewOf(s).tip_world);
}

TEST(VisualLive, BrokenPosesAreNamedAndDrawnAtRest) {
  thx_msgs::physics_poses_t m = posesAt(0.02);
  EXPECT_EQ(posesProblem(m), "");
  m.num_bodies = 33;
  EXPECT_EQ(posesProblem(m), "num_bodies 33; expected 0..32");
  EXPECT_TRUE(bodiesOf(m).empty());
  m = posesAt(0.02);
  m.q_world[0][0] = 0.0;  // not a rotation
  EXPECT_NE(posesProblem(m).find("body 0"), std::string::npos);
  EXPECT_TRUE(bodiesOf(m).empty());
}

std::string slurp(const fs::path& path) {
  std::ifstream f(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}

TEST(VisualLive, WithoutAServerTheSceneAtRest) {
  const fs::path dir = fs::path(::testing::TempDir()) / ("thx_visual_live_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string client = THX_VISUAL_CLIENT, scene = std::string(THX_SOURCE_DIR) + "/scenes/marble_bricks.yaml";
  const std::string common = " --scene " + scene + " --size 160x90 --elevation 60 --distance 0.08";
  // A bus port of this test's own (ttl=0): no hapticd answers there.
  const thx::test::PortBlock ports{static_cast<unsigned>(::getpid())};  // braces: clang read () as a declaration
  const std::string url = "'udpm://239.255.76.67:" + std::to_string(ports.firstPort()) + "?ttl=0'";
  const std::string live = "LP_NUM_THREADS=2 " + client + common + " --live --out " + (dir / "live").string() +
                           " --format ppm --lcm-url " + url + " --connect-timeout 0.3 2>" + (dir / "err.txt").string();
  ASSERT_EQ(std::system(live.c_str()), 0) << live;
  const std::string shot = "LP_NUM_THREADS=2 " + client + common + " --quiet --screenshot " + (dir / "rest.ppm").string();
  ASSERT_EQ(std::system(shot.c_str()), 0) << shot;
  ASSERT_TRUE(fs::exists(dir / "live" / "frame_0000.ppm"));
  EXPECT_FALSE(fs::exists(dir / "live" / "frame_0001.ppm"));
  EXPECT_TRUE(slurp(dir / "live" / "frame_0000.ppm") == slurp(dir / "rest.ppm"));
  const std::string err = slurp(dir / "err.txt");
  EXPECT_NE(err.find("drawing the scene at rest"), std::string::npos) << err;
  fs::remove_all(dir);
}

}  // namespace
}  // namespace thx::visual::test_live
