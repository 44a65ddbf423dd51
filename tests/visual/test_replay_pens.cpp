// Several pens (issue 30): a session of a multi-device scene becomes frames with every device's
// pen, each in its own colour, where that device's recorded states put it; --device N draws N's
// alone; a one-device session's frames stay one pen in the first colours; live views carry every
// device's pen and a move of any of them is a new frame.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <sstream>

#include "clients/visual/camera.hpp"
#include "clients/visual/live_view.hpp"
#include "clients/visual/options.hpp"
#include "clients/visual/replay_frames.hpp"
#include "scenes/scene_loader.hpp"
#include "scenes/scene_surface.hpp"
#include "server/session_log.hpp"
#include "tests/support/temp_dir.hpp"

namespace thx::visual::test_replay_pens {
namespace {

std::string slurp(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}

// Two devices' ticks as hapticd --record writes them (a tick's devices in index order, a hello
// naming both before the first tick): 1 s at 1 kHz, pen 0 sliding along +x at y = -0.03, pen 1
// still at (0.02, 0.03) with its proxy held on the plane; pen 1's ticks start at tick 200.
std::string recordTwoDevices(const test::TempDir& dir) {
  const std::string path = dir.file("two.lcm");
  srv::SessionRecorder rec(path, true);
  thx_msgs::hello_t hello{};
  hello.device_names = "left,right";
  hello.scene_name = "two pens";
  rec.recordHello(hello);
  for (std::int64_t t = 0; t < 1000; ++t) {
    srv::TickRecord r;
    r.tick = t;
    r.deadline_ns = t * 1'000'000;
    r.p_world[0] = r.proxy_world[0] = -0.02 + 4e-5 * double(t);
    r.p_world[1] = r.proxy_world[1] = -0.03;
    rec.record(r, 0);
    if (t < 200) continue;
    srv::TickRecord held = r;
    held.p_world[0] = held.proxy_world[0] = 0.02;
    held.p_world[1] = held.proxy_world[1] = 0.03;
    held.p_world[2] = -0.001;
    held.proxy_world[2] = 0.0;
    held.proxy_held = true;
    rec.record(held, 1);
  }
  EXPECT_TRUE(rec.ok()) << rec.error();
  return path;
}

TEST(VisualReplayPens, EachDevicesPenFromItsOwnStates) {
  const test::TempDir dir("visual_replay_pens");
  const std::vector<ReplayFrame> frames = replayFrames(recordTwoDevices(dir), 1000.0, 10.0, {1, 0});
  ASSERT_EQ(frames.size(), 10u);  // t = 0, 0.1, ..., 0.9 s
  for (std::size_t n = 0; n < frames.size(); ++n) {
    const std::vector<PenView> pens = pensOf(frames[n]);
    // Pen 1 has no state before tick 200: frames 0 and 1 draw pen 0 alone.
    ASSERT_EQ(pens.size(), n < 2 ? 1u : 2u) << n;
    EXPECT_EQ(pens[0].device, 0);
    EXPECT_EQ(frames[n].tick, std::int64_t(100 * n)) << n;
    EXPECT_DOUBLE_EQ(pens[0].tip_world.x(), -0.02 + 4e-5 * double(100 * n)) << n;
    EXPECT_DOUBLE_EQ(pens[0].tip_world.y(), -0.03);
    EXPECT_FALSE(pens[0].proxy_held);
    if (n < 2) continue;
    EXPECT_EQ(pens[1].device, 1);
    EXPECT_EQ(pens[1].tip_world, Eigen::Vector3d(0.02, 0.03, -0.001));
    EXPECT_TRUE(pens[1].proxy_held);
    EXPECT_EQ(pens[1].proxy_world, Eigen::Vector3d(0.02, 0.03, 0.0));
  }
  // One device of the two: its states alone, the first pen (its colour is its index's).
  const std::vector<ReplayFrame> right = replayFrames(dir.file("two.lcm"), 1000.0, 10.0, {1});
  ASSERT_EQ(right.size(), 8u);  // its ticks 200..999: t = 0 .. 0.7 s from its first
  EXPECT_EQ(right.front().tick, 200);
  EXPECT_EQ(right.front().device, 1);
  EXPECT_TRUE(right.front().other_pens.empty());
  // A device the log does not hold is named.
  try {
    replayFrames(dir.file("two.lcm"), 1000.0, 10.0, {0, 2});
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("no THX_DEVICE_STATE events of device 2"), std::string::npos) << e.what();
  }
}

TEST(VisualReplayPens, LiveViewsCarryEveryDevicesPen) {
  thx_msgs::device_state_t a{}, b{};
  a.p_world[0] = 0.01;
  b.device = 1;
  b.p_world[0] = 0.02;
  const LiveView both = liveViewOf(std::vector<thx_msgs::device_state_t>{a, b}, std::nullopt);
  const std::vector<PenView> pens = pensOf(both);
  ASSERT_EQ(pens.size(), 2u);
  EXPECT_EQ(pens[0].device, 0);
  EXPECT_EQ(pens[1].device, 1);
  EXPECT_DOUBLE_EQ(pens[1].tip_world.x(), 0.02);
  EXPECT_TRUE(sameView(both, liveViewOf(std::vector<thx_msgs::device_state_t>{a, b}, std::nullopt)));
  thx_msgs::device_state_t moved = b;
  moved.p_world[1] = 1e-6;  // the second pen alone moves: a new frame
  EXPECT_FALSE(sameView(both, liveViewOf(std::vector<thx_msgs::device_state_t>{a, moved}, std::nullopt)));
  EXPECT_FALSE(sameView(both, liveViewOf(a, std::nullopt)));  // a pen went away
  // One state: the one-pen view as before.
  EXPECT_TRUE(sameView(liveViewOf(a, std::nullopt), liveViewOf(std::vector<thx_msgs::device_state_t>{a}, std::nullopt)));
}

TEST(VisualReplayPens, DeviceOptionDrawsOnePen) {
  const std::vector<std::string> replay{"--scene", "s.yaml", "--replay-log", "s.lcm", "--out", "frames"};
  EXPECT_FALSE(parseOptions(replay).device.has_value());  // every device's pen
  std::vector<std::string> one = replay;
  one.insert(one.end(), {"--device", "1"});
  EXPECT_EQ(parseOptions(one).device, 1);
  try {
    parseOptions({"--scene", "s.yaml", "--screenshot", "x.png", "--device", "0"});
    FAIL() << "no error";
  } catch (const UsageError& e) {
    EXPECT_EQ(std::string(e.what()), "--device N picks a pen to draw: with --live or --replay-log");
  }
  EXPECT_NE(std::string(kHelp).find("Default: every device's pen"), std::string::npos);
}

// A binary PPM read whole.
struct Ppm {
  int width = 0, height = 0;
  std::string rgb;
  std::array<int, 3> at(int x, int y) const {
    const std::size_t i = (std::size_t(y) * std::size_t(width) + std::size_t(x)) * 3;
    return {(unsigned char)rgb[i], (unsigned char)rgb[i + 1], (unsigned char)rgb[i + 2]};
  }
};

Ppm readPpm(const std::string& path) {
  std::istringstream in(slurp(path));
  std::string magic;
  int max = 0;
  Ppm p;
  in >> magic >> p.width >> p.height >> max;
  in.get();
  p.rgb.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  EXPECT_EQ(magic, "P6") << path;
  EXPECT_EQ(p.rgb.size(), std::size_t(p.width) * std::size_t(p.height) * 3) << path;
  return p;
}

// Whose colours a pixel shows: device 0's (red, held yellow: red 1.5 x blue and more), device
// 1's (blue, held cyan: blue 1.5 x red and more), else -1 (the plane's grey-beige, red 1.1 x blue
// under a white light; the shafts' grey; the background). Dark pixels count as neither.
int penColourOf(const std::array<int, 3>& c) {
  if (c[0] > 60 && 2 * c[0] > 3 * c[2]) return 0;
  if (c[2] > 60 && 2 * c[2] > 3 * c[0]) return 1;
  return -1;
}

// Where a pen's ball is on screen (pixels from the top-left corner): the proxy while held, else
// the tip.
Eigen::Vector2d projected(const Camera& camera, const Ppm& frame, const PenView& pen) {
  const Eigen::Vector3d p = pen.proxy_held ? pen.proxy_world : pen.tip_world;
  const Eigen::Vector4d clip = camera.viewProjection() * Eigen::Vector4d(p.x(), p.y(), p.z(), 1.0);
  const Eigen::Vector2d ndc = clip.head<2>() / clip.w();
  return {(ndc.x() + 1) / 2 * frame.width, (1 - ndc.y()) / 2 * frame.height};
}

// Pixels of each pen colour in `frame`: within `radius` px of the ball of a pen of that colour's
// device, and anywhere else.
struct ColourCount {
  int near = 0, elsewhere = 0;
};
std::array<ColourCount, 2> countPenColours(const Ppm& frame, const Camera& camera, const std::vector<PenView>& pens,
                                           double radius) {
  std::array<ColourCount, 2> counts{};
  for (int y = 0; y < frame.height; ++y) {
    for (int x = 0; x < frame.width; ++x) {
      const int k = penColourOf(frame.at(x, y));
      if (k < 0) continue;
      bool near = false;
      for (const PenView& pen : pens) {
        const double d = (projected(camera, frame, pen) - Eigen::Vector2d(x + 0.5, y + 0.5)).norm();
        near = near || (pen.device == k && d <= radius);
      }
      ++(near ? counts[std::size_t(k)].near : counts[std::size_t(k)].elsewhere);
    }
  }
  return counts;
}

// visual-client --replay-log `log` on `scene` into dir/out (ppm frames every half second, 640x360,
// looking down on the middle of the plane), and the camera it draws them with.
struct ReplayRun {
  const test::TempDir& dir;
  std::string scene, log;
  std::vector<std::string> view() const {
    return {"--scene", scene, "--replay-log", log, "--size", "640x360", "--elevation", "70", "--distance", "0.16",
            "--format", "ppm", "--rate", "2", "--quiet"};
  }
  void run(const std::string& out, const std::string& extra) const {
    std::string cmd = "LP_NUM_THREADS=2 " + std::string(THX_VISUAL_CLIENT);
    for (const std::string& a : view()) cmd += " " + a;
    cmd += " --out " + dir.file(out) + extra;
    ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  }
  Camera camera() const {
    std::vector<std::string> args = view();
    args.insert(args.end(), {"--out", "unused"});
    const Options o = parseOptions(args);
    const scene::Scene s = scene::loadScene(scene);
    return Camera(cameraPlacement(o, s), scene::buildSceneSurface(s).surface.mapping().plane_to_world, o.width, o.height);
  }
  Ppm frame(const std::string& out, std::size_t f) const {
    char name[32];
    std::snprintf(name, sizeof name, "/frame_%04zu.ppm", f);
    return readPpm(dir.file(out) + name);
  }
};

TEST(VisualReplayPens, ARecordedTwoPenSessionDrawsBothPensWhereTheyAre) {
  const test::TempDir dir("visual_two_pens");
  const ReplayRun replay{dir, std::string(THX_SOURCE_DIR) + "/scenes/two_pens.yaml", dir.file("two_pens.lcm")};
  const std::string hd = std::string(THX_HAPTICD) + " --scene " + replay.scene +
                         " --lockstep --no-lcm --no-mlock --quiet --duration 2 --record " + replay.log +
                         " --flight-dir " + dir.file("") + " > /dev/null";
  ASSERT_EQ(std::system(hd.c_str()), 0) << hd;
  replay.run("both", "");
  replay.run("right", " --device 1");
  const Camera camera = replay.camera();
  const std::vector<ReplayFrame> frames = replayFrames(replay.log, 1000.0, 2.0, {0, 1});
  ASSERT_GE(frames.size(), 4u);  // 2 s of ticks: t = 0, 0.5, 1, 1.5 s (and 2 s if a tick is there)
  for (std::size_t f = 0; f < frames.size(); ++f) {
    const std::vector<PenView> pens = pensOf(frames[f]);
    ASSERT_EQ(pens.size(), 2u) << f;
    const std::array<ColourCount, 2> both = countPenColours(replay.frame("both", f), camera, pens, 16.0);
    const std::array<ColourCount, 2> right = countPenColours(replay.frame("right", f), camera, pens, 16.0);
    std::printf("frame %zu: left pen (%+.4f, %+.4f)%s %d px near, %d elsewhere; right pen (%+.4f, %+.4f)%s %d / %d; "
                "--device 1: left %d / %d, right %d / %d\n",
                f, pens[0].tip_world.x(), pens[0].tip_world.y(), pens[0].proxy_held ? " held" : "", both[0].near,
                both[0].elsewhere, pens[1].tip_world.x(), pens[1].tip_world.y(), pens[1].proxy_held ? " held" : "",
                both[1].near, both[1].elsewhere, right[0].near, right[0].elsewhere, right[1].near, right[1].elsewhere);
    // Each pen's colours around its own ball, and nowhere else.
    EXPECT_GE(both[0].near, 12) << f;
    EXPECT_GE(both[1].near, 12) << f;
    EXPECT_EQ(both[0].elsewhere, 0) << f;
    EXPECT_EQ(both[1].elsewhere, 0) << f;
    // --device 1: the right pen alone, as many pixels of it as in the frame of both.
    EXPECT_EQ(right[0].near + right[0].elsewhere, 0) << f;
    EXPECT_EQ(right[1].near, both[1].near) << f;
    EXPECT_EQ(right[1].elsewhere, 0) << f;
  }
}

// A log without a hello is one device's whole, whatever its `device` fields hold (sessions
// recorded before they were filled): one pen, in device 0's colours, where the states put it.
TEST(VisualReplayPens, AOneDeviceLogIsOnePenInTheFirstColours) {
  const test::TempDir dir("visual_one_pen");
  const ReplayRun replay{dir, std::string(THX_SOURCE_DIR) + "/scenes/two_pens.yaml", dir.file("one.lcm")};
  {
    srv::SessionRecorder rec(replay.log, true);
    for (std::int64_t t = 0; t < 1000; ++t) {
      srv::TickRecord r;
      r.tick = t;
      r.deadline_ns = t * 1'000'000;
      r.p_world[0] = r.proxy_world[0] = 0.03 - 6e-5 * double(t);
      r.p_world[1] = r.proxy_world[1] = 0.01;
      rec.record(r, 3);  // a field no hello explains
    }
    ASSERT_TRUE(rec.ok()) << rec.error();
  }
  replay.run("one", "");
  replay.run("device0", " --device 0");
  const Camera camera = replay.camera();
  const std::vector<ReplayFrame> frames = replayFrames(replay.log, 1000.0, 2.0);
  ASSERT_EQ(frames.size(), 2u);  // t = 0 and 0.5 s
  for (std::size_t f = 0; f < frames.size(); ++f) {
    const std::vector<PenView> pens = pensOf(frames[f]);
    ASSERT_EQ(pens.size(), 1u);
    EXPECT_EQ(pens[0].device, 0);
    const std::array<ColourCount, 2> one = countPenColours(replay.frame("one", f), camera, pens, 16.0);
    std::printf("one-device frame %zu: pen (%+.4f, %+.4f) %d px near, %d elsewhere; device 1's colours %d\n", f,
                pens[0].tip_world.x(), pens[0].tip_world.y(), one[0].near, one[0].elsewhere, one[1].near + one[1].elsewhere);
    EXPECT_GE(one[0].near, 12) << f;
    EXPECT_EQ(one[0].elsewhere + one[1].near + one[1].elsewhere, 0) << f;
    EXPECT_TRUE(slurp(dir.file("one/frame_000" + std::to_string(f) + ".ppm")) ==
                slurp(dir.file("device0/frame_000" + std::to_string(f) + ".ppm")))
        << f;
  }
}

}  // namespace
}  // namespace thx::visual::test_replay_pens
