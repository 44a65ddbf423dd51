// --replay-log (issue 15): a recorded session becomes frames deterministically: one per 1/rate
// of recorded time, the pen where the latest device state at or before it put it (missed ticks
// included); bad files name the problem; two runs write identical frames.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "clients/visual/replay_frames.hpp"
#include "server/session_log.hpp"

namespace thx::visual {
namespace {

namespace fs = std::filesystem;

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::path(::testing::TempDir()) / ("thx_visual_replay_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir / name;
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

}  // namespace
}  // namespace thx::visual
