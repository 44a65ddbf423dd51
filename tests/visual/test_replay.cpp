// --replay-log (issue 15): a recorded session becomes frames deterministically: one per 1/rate
// of recorded time, the pen (tip and proxy) where the latest device state at or before it put it
// (missed ticks included), the bodies at the latest physics poses by then; bad files name the
// problem; two runs write identical frames.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>

#include <lcm/lcm-cpp.hpp>
#include <thx_msgs/physics_poses_t.hpp>
#include <thx_msgs/protocol.hpp>

#include "clients/visual/replay_frames.hpp"
#include "server/session_log.hpp"
#include "tests/support/temp_dir.hpp"

namespace thx::visual::test_replay {
namespace {

namespace fs = std::filesystem;

// One folder per process, removed with its files when the process ends.
fs::path scratch(const std::string& name) {
  static const test::TempDir dir("thx_visual_replay");
  return dir.path() / name;
}

// 1 s at 1 kHz, the tip sliding along x 1 mm below the plane; ticks 500..549 missed.
std::string recordSession() {
  const std::string path = scratch("session.lcm").string();
  srv::SessionRecorder rec(path, true);
  for (std::int64_t t = 0; t < 1000; ++t) {
    if (t >= 500 && t < 550) continue;
    srv::TickRecord r;
    r.tick = t + 7;  // a session does not start at tick 0
    r.deadline_ns = r.tick * 1'000'000;
    r.p_world[0] = -0.02 + 4e-5 * double(t);
    r.p_world[2] = -0.001;
    rec.record(r);
  }
  EXPECT_TRUE(rec.ok()) << rec.error();
  return path;
}

// A combined session as `physics-client --replay-log S --record OUT` writes one: 1 s at 1 kHz, the
// pen still at (0.01, 0.01), 1 mm below the plane with its proxy held on it; the scene's one body
// (marble_bricks' marble) published at 100 Hz on the device's clock, rolling 20 mm along +x from
// t = 0.5 s, at rest at its scene position before.
constexpr double kMarbleX = 0.03, kMarbleY = -0.01, kMarbleZ = 0.00578;
std::string recordCombinedSession() {
  const std::string path = scratch("combined.lcm").string();
  {
    srv::SessionRecorder rec(path, true);
    for (std::int64_t t = 0; t < 1000; ++t) {
      srv::TickRecord r;
      r.tick = t;
      r.deadline_ns = t * 1'000'000;
      r.p_world[0] = r.p_world[1] = 0.01;
      r.p_world[2] = -0.001;
      r.proxy_held = true;
      r.proxy_world[0] = r.proxy_world[1] = 0.01;
      rec.record(r);
    }
    EXPECT_TRUE(rec.ok()) << rec.error();
  }
  lcm::LogFile log(path, "a");
  for (int n = 0; n < 100; ++n) {
    thx_msgs::physics_poses_t m{};
    m.utime = n * 10'000;
    m.seq = n + 1;
    m.ref_tick = n * 10;
    m.num_bodies = 1;
    const double moved = n >= 50 ? 4e-4 * double(n - 50) : 0.0;
    m.p_world[0][0] = kMarbleX + moved;
    m.p_world[0][1] = kMarbleY;
    m.p_world[0][2] = kMarbleZ;
    m.q_world[0][0] = 1.0;
    std::vector<std::uint8_t> bytes(std::size_t(m.getEncodedSize()));
    m.encode(bytes.data(), 0, int(bytes.size()));
    lcm::LogEvent e{};
    e.timestamp = m.utime;
    e.channel = thx_msgs::kChannelPhysicsPoses;
    e.datalen = std::int32_t(bytes.size());
    e.data = bytes.data();
    EXPECT_EQ(log.writeEvent(&e), 0);
  }
  return path;
}

std::string slurp(const fs::path& path) {
  std::ifstream f(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}

TEST(VisualReplay, OneFramePerPeriodWithTheLatestRecordedPen) {
  const std::vector<ReplayFrame> frames = replayFrames(recordSession(), 1000.0, 30.0);
  ASSERT_EQ(frames.size(), 30u);  // t = 0, 1/30, ..., 29/30 <= 0.999 s
  for (std::size_t n = 0; n < frames.size(); ++n) {
    std::int64_t t = std::int64_t(std::floor(double(n) * 1000.0 / 30.0 + 1e-9));
    if (t >= 500 && t < 550) t = 499;  // missed ticks: the latest state before them
    EXPECT_EQ(frames[n].tick, t + 7) << n;
    EXPECT_DOUBLE_EQ(frames[n].tip_world.x(), -0.02 + 4e-5 * double(t)) << n;
    EXPECT_DOUBLE_EQ(frames[n].tip_world.z(), -0.001);
    EXPECT_DOUBLE_EQ(frames[n].t_s, double(n) / 30.0);
  }
}

TEST(VisualReplay, ProxyAndBodiesComeFromTheLog) {
  const std::vector<ReplayFrame> frames = replayFrames(recordCombinedSession(), 1000.0, 10.0);
  ASSERT_EQ(frames.size(), 10u);
  for (std::size_t n = 0; n < frames.size(); ++n) {
    EXPECT_TRUE(frames[n].proxy_held) << n;
    EXPECT_DOUBLE_EQ(frames[n].proxy_world.z(), 0.0) << n;
    EXPECT_DOUBLE_EQ(frames[n].tip_world.z(), -0.001) << n;
    ASSERT_EQ(frames[n].bodies.size(), 1u) << n;
    // Frame n is at tick 100 n: the poses published at utime 100 n ms (the same clock), n * 10.
    const double moved = n >= 5 ? 4e-4 * double(10 * n - 50) : 0.0;
    EXPECT_DOUBLE_EQ(frames[n].bodies[0].translation().x(), kMarbleX + moved) << n;
  }
  // A session without physics poses: no bodies (drawn at rest), the proxy as recorded.
  const std::vector<ReplayFrame> pen_only = replayFrames(recordSession(), 1000.0, 30.0);
  EXPECT_TRUE(pen_only.front().bodies.empty());
  EXPECT_FALSE(pen_only.front().proxy_held);
  EXPECT_EQ(pen_only.front().proxy_world, pen_only.front().tip_world);
}

TEST(VisualReplay, NotASessionLogNamesTheFile) {
  const fs::path bad = scratch("not_a_log.lcm");
  std::ofstream(bad) << "hello\n";
  try {
    replayFrames(bad.string(), 1000.0, 30.0);
    FAIL() << "no error";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find(bad.string()), std::string::npos) << m;
    EXPECT_NE(m.find("expected a session log (LCM log) from `hapticd --record`"), std::string::npos) << m;
  }
}

TEST(VisualReplay, TwoRunsWriteTheSameFramesAndThePenMoves) {
  const std::string log = recordSession();
  const std::string client = THX_VISUAL_CLIENT, scene = std::string(THX_SOURCE_DIR) + "/scenes/marble_bricks.yaml";
  const auto run = [&](const fs::path& out) {
    const std::string cmd = "LP_NUM_THREADS=2 " + client + " --scene " + scene + " --replay-log " + log +
                            " --out " + out.string() + " --frames 3 --rate 2 --size 96x64 --format ppm --quiet" +
                            " --elevation 60 --distance 0.08";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  };
  const fs::path a = scratch("a"), b = scratch("b");
  run(a);
  run(b);
  for (const char* f : {"frame_0000.ppm", "frame_0001.ppm"}) {
    ASSERT_TRUE(fs::exists(a / f)) << f;
    EXPECT_TRUE(slurp(a / f) == slurp(b / f)) << f;
  }
  EXPECT_FALSE(fs::exists(a / "frame_0002.ppm"));  // 2 Hz over 0.999 s: t = 0 and 0.5 only
  EXPECT_FALSE(slurp(a / "frame_0000.ppm") == slurp(a / "frame_0001.ppm")) << "the pen did not move";
}

TEST(VisualReplay, TwoRunsOfACombinedSessionAreIdenticalAndTheMarbleMoves) {
  const std::string log = recordCombinedSession();
  const std::string client = THX_VISUAL_CLIENT, scene = std::string(THX_SOURCE_DIR) + "/scenes/marble_bricks.yaml";
  const auto run = [&](const fs::path& out) {
    // Looking down on the marble from above its rolling path: 160x90.
    const std::string cmd = "LP_NUM_THREADS=2 " + client + " --scene " + scene + " --replay-log " + log +
                            " --out " + out.string() + " --rate 2 --size 160x90 --format ppm --quiet" +
                            " --elevation 70 --distance 0.08 --target 0.035,-0.01";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  };
  const fs::path a = scratch("combined_a"), b = scratch("combined_b");
  run(a);
  run(b);
  for (const char* f : {"frame_0000.ppm", "frame_0001.ppm"}) {
    ASSERT_TRUE(fs::exists(a / f)) << f;
    EXPECT_TRUE(slurp(a / f) == slurp(b / f)) << f;
  }
  // t = 0: the marble at rest; t = 0.5 s: the pose of tick 500, still at rest; a third frame
  // would be at 1 s, after the log. The pen stands still: only the marble can change a frame.
  EXPECT_TRUE(slurp(a / "frame_0000.ppm") == slurp(a / "frame_0001.ppm"));
  const fs::path c = scratch("combined_c");
  const std::string cmd = "LP_NUM_THREADS=2 " + client + " --scene " + scene + " --replay-log " + log + " --out " +
                          c.string() + " --rate 1.2 --size 160x90 --format ppm --quiet" +
                          " --elevation 70 --distance 0.08 --target 0.035,-0.01";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  // 1.2 Hz: t = 0 and 0.833 s, where the marble has rolled 13 mm.
  ASSERT_TRUE(fs::exists(c / "frame_0001.ppm"));
  EXPECT_TRUE(slurp(c / "frame_0000.ppm") == slurp(a / "frame_0000.ppm"));
  EXPECT_FALSE(slurp(c / "frame_0001.ppm") == slurp(c / "frame_0000.ppm")) << "the marble did not move";
}

TEST(VisualReplay, ACombinedSessionOnAMeshSceneDrawsItsMarbleWhereThePosesPutIt) {
  // The bowl of bricks, coarse, with marble_bricks' marble where the combined session has it.
  const fs::path scene = scratch("marble_in_a_bowl.yaml");
  std::ofstream(scene) << "version: 1\nname: marble in a bowl\nsurface:\n  size: [0.04, 0.04]\n"
                          "  mesh: {generator: bowl, size: 0.06, segments: 32, closed: true}\n"
                          "  pose: {position: [0.0, 0.0, -0.04], rpy_deg: [0.0, 0.0, 0.0]}\n"
                          "  texture: {generator: bricks, size: 64, params: {extent: 0.04}}\n"
                          "objects:\n  - {name: marble, shape: sphere, radius: 0.01, mass: 0.02, position: [0.03, -0.01, 0.00578]}\n";
  const std::string log = recordCombinedSession();
  const auto run = [&](const fs::path& out, const std::string& extra) {
    const std::string cmd = "LP_NUM_THREADS=2 " + std::string(THX_VISUAL_CLIENT) + " --scene " + scene.string() +
                            " --replay-log " + log + " --out " + out.string() +
                            " --rate 1.2 --size 160x90 --format ppm --quiet --elevation 70 --distance 0.12" + extra;
    ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  };
  const fs::path with = scratch("mesh_marble"), without = scratch("mesh_no_objects");
  run(with, "");
  run(without, " --no-objects");
  // t = 0 and 0.833 s, where the marble has rolled 13 mm; the pen stands still.
  ASSERT_TRUE(fs::exists(with / "frame_0001.ppm"));
  EXPECT_FALSE(slurp(with / "frame_0001.ppm") == slurp(with / "frame_0000.ppm")) << "the marble did not move";
  EXPECT_TRUE(slurp(without / "frame_0001.ppm") == slurp(without / "frame_0000.ppm"));
  EXPECT_FALSE(slurp(with / "frame_0000.ppm") == slurp(without / "frame_0000.ppm")) << "no marble drawn";
}

}  // namespace
}  // namespace thx::visual::test_replay
