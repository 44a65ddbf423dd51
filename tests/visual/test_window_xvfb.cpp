// The window presenter under a virtual X server (issue 15): visual-client --window draws the same
// pixels the headless path writes (one render path into a framebuffer, two presenters). Runs both
// as processes; skipped when xvfb-run (Debian package xvfb) is missing.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace test_window_xvfb {

namespace {

std::string slurp(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}

TEST(VisualWindow, WindowUnderXvfbShowsTheHeadlessFrame) {
  if (std::system("command -v xvfb-run > /dev/null 2>&1") != 0) GTEST_SKIP() << "xvfb-run missing (Debian: xvfb)";
  const std::filesystem::path dir = std::filesystem::path(::testing::TempDir()) / "visual_window_xvfb";
  std::filesystem::create_directories(dir);
  const std::string client = THX_VISUAL_CLIENT, scene = std::string(THX_SOURCE_DIR) + "/scenes/marble_bricks.yaml";
  const std::string common = " --scene " + scene + " --size 160x96 --mode relief --quiet";
  const std::string window = (dir / "window.ppm").string(), headless = (dir / "headless.ppm").string();
  const std::string run_window = "LP_NUM_THREADS=2 xvfb-run -a -s '-screen 0 640x480x24 -nolisten tcp' " + client +
                                 common + " --window-frames 2 --window-screenshot " + window;
  const std::string run_headless = "LP_NUM_THREADS=2 " + client + common + " --screenshot " + headless;
  ASSERT_EQ(std::system(run_window.c_str()), 0) << run_window;
  ASSERT_EQ(std::system(run_headless.c_str()), 0) << run_headless;
  const std::string a = slurp(window), b = slurp(headless);
  ASSERT_EQ(a.size(), std::size_t(14 + 160 * 96 * 3));  // "P6\n160 96\n255\n" + RGB
  EXPECT_TRUE(a == b) << "the window's frame differs from the headless frame";
}

TEST(VisualWindow, NoDisplayIsAClearError) {
  const std::string client = THX_VISUAL_CLIENT, scene = std::string(THX_SOURCE_DIR) + "/scenes/marble_bricks.yaml";
  const std::filesystem::path out = std::filesystem::path(::testing::TempDir()) / "visual_no_display.txt";
  const std::string cmd = "env -u DISPLAY " + client + " --scene " + scene + " --window --quiet 2> " + out.string();
  const int status = std::system(cmd.c_str());
  EXPECT_EQ(WEXITSTATUS(status), 1);
  EXPECT_NE(slurp(out.string()).find("window: DISPLAY is not set: run under xvfb-run -a (Debian package xvfb)"),
            std::string::npos)
      << slurp(out.string());
}

}  // namespace

}  // namespace test_window_xvfb
