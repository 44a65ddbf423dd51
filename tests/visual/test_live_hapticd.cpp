// visual-client --live beside a running hapticd (processes, on a bus port of the test's own): it
// connects through the client kit, draws the pen as the device state moves it, follows a scene
// switch another client asks for, and prints its summary. Only what does not depend on the
// scheduler is asserted: that it connected, drew a first frame, followed the one switch, and
// counted its frames; how many are drawn or skipped is the machine's business.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <set>

#include "tests/support/hapticd_harness.hpp"
#include "thx_client/app.hpp"

namespace thx::test::test_live_hapticd {
namespace {

struct VisualLiveHapticd : HapticdProcessTest {
  // Waits until the text of `file` holds `text`.
  bool logHas(const std::string& file, const std::string& text, double timeout_s) {
    return waitUntil([&] { return slurp(file).find(text) != std::string::npos; }, timeout_s);
  }
  // A visual client live and drawing: connected, its first frame written.
  void expectLive(const std::string& err) {
    ASSERT_TRUE(logHas(err, "visual-client: live from", 30)) << slurp(err);
    ASSERT_TRUE(waitUntil([&] { return fs::exists(path("frames/frame_0000.ppm")); }, 30));
  }
  // visual-client live on `scene`, headless into frames/; it runs until the test ends it (the
  // 300 s are only a bound: the test's own waits could add up to more than a shorter run).
  std::vector<std::string> liveArgs(const std::string& scene) {
    return {THX_VISUAL_CLIENT, "--scene", scene, "--live", "--lcm-url", url_, "--out", path("frames"), "--format",
            "ppm", "--size", "160x90", "--rate", "30", "--duration", "300", "--connect-timeout", "20"};
  }
  // Ends it as a user would (SIGTERM) and returns what it said.
  std::string stopVisual(pid_t visual) {
    kill(visual, SIGTERM);
    EXPECT_EQ(reap(visual, 20), 0) << slurp(path("visual.err"));
    return slurp(path("visual.err"));
  }
  // Runs visual-client with `args` while hapticd switches to `scene`; waits until its log says
  // `said`, ends it and returns its log.
  std::string liveThroughSwitch(const std::vector<std::string>& args, const std::string& scene, const std::string& said) {
    const pid_t visual = spawn(args, path("visual.out"), path("visual.err"));
    EXPECT_GT(visual, 0);
    expectLive(path("visual.err"));
    switchServer(scene);
    EXPECT_TRUE(logHas(path("visual.err"), said, 30)) << slurp(path("visual.err"));
    return stopVisual(visual);
  }
  // Another client asks hapticd to switch to `scene`.
  void switchServer(const std::string& scene) {
    client::AppOptions o;
    o.client_id = "switcher";
    o.lcm_url = url_;
    client::ClientApp app(o);
    ASSERT_TRUE(app.waitForServer());
    ASSERT_TRUE(app.loadScene(scene, 20));
  }
};

TEST_F(VisualLiveHapticd, DrawsTheServersPenAndFollowsASceneSwitch) {
  if (!udpmAvailable()) GTEST_SKIP() << "no multicast route for " << url_;
  startServer({});
  // The visual client follows: it loads vvalley from its scenes folder and draws on.
  const std::string err =
      liveThroughSwitch(liveArgs("scenes/default.yaml"), "vvalley", "visual-client: hapticd switched to scene vvalley\n");
  EXPECT_NE(err.find("visual-client: live: loop steps"), std::string::npos) << err;
  EXPECT_NE(err.find("scene switches 1"), std::string::npos) << err;
  stopServer();
}

// The user study's candidate looks (docs/study.md §7): --allow-different-scene draws its own
// scene's look beside a hapticd running another, and keeps it through hapticd's switches;
// without it the other scene is an error naming both.
TEST_F(VisualLiveHapticd, AnotherLookWithAllowDifferentScene) {
  if (!udpmAvailable()) GTEST_SKIP() << "no multicast route for " << url_;
  startServer({});
  const pid_t refused = spawn(liveArgs("scenes/vvalley.yaml"), path("refused.out"), path("refused.err"));
  ASSERT_GT(refused, 0);
  EXPECT_NE(reap(refused, 60), 0);
  EXPECT_NE(slurp(path("refused.err")).find("vvalley"), std::string::npos) << slurp(path("refused.err"));

  std::vector<std::string> args = liveArgs("scenes/vvalley.yaml");
  args.push_back("--allow-different-scene");
  const std::string err =
      liveThroughSwitch(args, "pinball", "visual-client: hapticd switched to scene pinball; drawing ours");
  EXPECT_NE(err.find("scene switches 0"), std::string::npos) << err;
  stopServer();
}

// A server with two devices (scenes/two_pens.yaml): once their states arrive, a frame holds both
// pens, device 0's in red (yellow held) and device 1's in blue (cyan held). Before any state the
// pens rest in the same colours, so whichever frame is the newest when the client is stopped holds
// both.
TEST_F(VisualLiveHapticd, DrawsEveryPenOfATwoDeviceServer) {
  if (!udpmAvailable()) GTEST_SKIP() << "no multicast route for " << url_;
  startServer({"--scene", "scenes/two_pens.yaml"});
  std::vector<std::string> args = liveArgs("scenes/two_pens.yaml");
  args.insert(args.end(), {"--size", "640x360", "--elevation", "70", "--distance", "0.16"});
  const pid_t visual = spawn(args, path("visual.out"), path("visual.err"));
  ASSERT_GT(visual, 0);
  expectLive(path("visual.err"));
  // A frame is drawn only when something moved, and the pens' scripts end after about 5 s: a
  // client that starts slowly (the sanitizer tree beside busy cores) draws only a few, and one
  // that starts after the scripts have ended draws only its first. Every frame has both pens (a
  // pen with no state yet rests where its script starts), so the first frame is what is waited
  // for; a second, if the pens still move, is given a moment but not required.
  ASSERT_TRUE(waitUntil([&] { return fs::exists(path("frames/frame_0000.ppm")); }, 30)) << slurp(path("visual.err"));
  waitUntil([&] { return fs::exists(path("frames/frame_0001.ppm")); }, 3);
  const std::string err = stopVisual(visual);
  EXPECT_NE(err.find("visual-client: live: loop steps"), std::string::npos) << err;
  stopServer();
  std::string newest;
  for (const auto& e : fs::directory_iterator(path("frames"))) newest = std::max(newest, e.path().string());
  const std::string ppm = slurp(newest);
  ASSERT_EQ(ppm.size(), std::size_t(15 + 640 * 360 * 3));  // "P6\n640 360\n255\n" + RGB
  int first = 0, second = 0;  // pixels in device 0's and device 1's colours (the plane is grey-beige)
  for (std::size_t p = 15; p + 2 < ppm.size(); p += 3) {
    const int r = (unsigned char)ppm[p], b = (unsigned char)ppm[p + 2];
    first += r > 60 && 2 * r > 3 * b;
    second += b > 60 && 2 * b > 3 * r;
  }
  std::printf("%s: %d px in device 0's colours, %d in device 1's\n", newest.c_str(), first, second);
  // Each pen is drawn in its colours. How many pixels depends on where each pen is when the newest
  // frame is drawn, which depends on the scheduler (6 to 43 px seen; a held ball is half below the
  // brick face), so only their presence is asserted; VisualReplayPens counts them deterministically.
  EXPECT_GE(first, 1) << newest;
  EXPECT_GE(second, 1) << newest;
}

TEST_F(VisualLiveHapticd, InAWindowUnderXvfb) {
  if (!udpmAvailable()) GTEST_SKIP() << "no multicast route for " << url_;
  if (std::system("command -v xvfb-run > /dev/null 2>&1") != 0) GTEST_SKIP() << "xvfb-run missing (Debian: xvfb)";
  startServer({});
  const std::string cmd = "cd '" + std::string(THX_SOURCE_DIR) +
                          "' && LP_NUM_THREADS=2 xvfb-run -a -s '-screen 0 640x480x24 -nolisten tcp' '" +
                          THX_VISUAL_CLIENT + "' --scene scenes/default.yaml --live --window --window-frames 5" +
                          " --window-screenshot '" + path("window.ppm") + "' --size 160x90 --connect-timeout 20" +
                          " --lcm-url '" + url_ + "' 2>'" + path("window.err") + "'";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd << "\n" << slurp(path("window.err"));
  const std::string err = slurp(path("window.err"));
  EXPECT_NE(err.find("visual-client: live from"), std::string::npos) << err;
  EXPECT_NE(err.find("window closed after 5 frames"), std::string::npos) << err;
  const std::string ppm = slurp(path("window.ppm"));
  ASSERT_EQ(ppm.size(), std::size_t(14 + 160 * 90 * 3));  // "P6\n160 90\n255\n" + RGB
  // Content, not a blank window: many pixels show the lit plane (not the clear colour, 20 23 28)
  // and the shading varies across it.
  int plane = 0;
  std::set<int> shades;
  for (std::size_t p = 14; p + 2 < ppm.size(); p += 3) {
    const int r = (unsigned char)ppm[p], g = (unsigned char)ppm[p + 1], b = (unsigned char)ppm[p + 2];
    if (std::abs(r - 20) + std::abs(g - 23) + std::abs(b - 28) > 24) ++plane;
    shades.insert((r << 16) | (g << 8) | b);
  }
  EXPECT_GT(plane, 160 * 90 / 4) << "pixels that are not the background";  // measured 6977 (48 %)
  EXPECT_GT(shades.size(), 32u) << "distinct colours in the frame";
  stopServer();
}

}  // namespace
}  // namespace thx::test::test_live_hapticd
