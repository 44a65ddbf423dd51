// visual-client --surface-mesh (issue 28): a built-in textured mesh drawn instead of the plane,
// headless; the command line refuses what the mesh does not draw, naming the option. A mesh scene
// (surface.mesh) is drawn from its own mesh, a recorded session of it with the pen, and --window
// or --live refuse it by name.
#include <gtest/gtest.h>

#include <array>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

#include "clients/visual/options.hpp"
#include "tests/support/temp_dir.hpp"

namespace thx::visual::test_mesh_client {
namespace {

std::string messageOf(const std::vector<std::string>& args) {
  try {
    parseOptions(args);
  } catch (const std::exception& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(VisualMeshClient, CommandLineMistakesNameTheOption) {
  const std::vector<std::string> shot{"--scene", "s.yaml", "--screenshot", "x.png", "--surface-mesh"};
  const auto with = [&](std::vector<std::string> more) {
    std::vector<std::string> a = shot;
    a.insert(a.end(), more.begin(), more.end());
    return messageOf(a);
  };
  EXPECT_EQ(with({"cube"}), "--surface-mesh: expected sphere|cylinder|torus|bowl|vase|box|room|plate, got 'cube'");
  EXPECT_EQ(with({"vase", "--mode", "mesh:16"}), "--surface-mesh: --mode normal or relief (mesh:N displaces the plane's grid)");
  EXPECT_EQ(with({"vase", "--search", "maxmip"}), "--surface-mesh: --search linear (the max-mipmap walk is the plane's)");
  EXPECT_EQ(with({"vase", "--pen", "0,0"}), "--surface-mesh draws no pen: not with --pen");
  EXPECT_EQ(messageOf({"--scene", "s.yaml", "--window", "--surface-mesh", "torus"}),
            "--surface-mesh draws headless: with --screenshot FILE or --frames N --out DIR");
  EXPECT_EQ(messageOf({"--scene", "s.yaml", "--screenshot", "x.png", "--surface-mesh-tile", "0.1"}),
            "--surface-mesh-tile M needs --surface-mesh SHAPE");
  const Options ok = parseOptions({"--scene", "s.yaml", "--screenshot", "x.png", "--surface-mesh", "bowl",
                                   "--surface-mesh-tile", "0.05", "--mode", "normal"});
  EXPECT_EQ(ok.surface_mesh, "bowl");
  EXPECT_DOUBLE_EQ(ok.surface_mesh_tile_m, 0.05);
  EXPECT_NE(std::string(kHelp).find("--surface-mesh SHAPE"), std::string::npos);
}

// A binary PPM's pixel (x, y) as r, g, b.
std::array<int, 3> ppmPixel(const std::string& ppm, int x, int y) {
  std::istringstream in(ppm);
  std::string magic;
  int w = 0, h = 0, max = 0;
  in >> magic >> w >> h >> max;
  in.get();
  const std::size_t at = std::size_t(in.tellg()) + (std::size_t(y) * std::size_t(w) + std::size_t(x)) * 3;
  EXPECT_EQ(magic, "P6");
  EXPECT_LT(at + 2, ppm.size());
  return {(unsigned char)ppm[at], (unsigned char)ppm[at + 1], (unsigned char)ppm[at + 2]};
}

TEST(VisualMeshClient, DrawsTheMeshWhereTheCameraLooks) {
  const test::TempDir dir("visual_mesh_client");
  const std::string scene = std::string(THX_SOURCE_DIR) + "/scenes/marble_bricks.yaml";
  for (const char* shape : {"sphere", "vase"}) {
    const std::string out = dir.file(std::string(shape) + ".ppm");
    const std::string cmd = std::string("LP_NUM_THREADS=2 ") + THX_VISUAL_CLIENT + " --scene " + scene +
                            " --surface-mesh " + shape + " --screenshot " + out + " --size 96x64 --quiet";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
    std::ifstream f(out, std::ios::binary);
    const std::string ppm((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    // The background (FrameRenderer's clear colour, 0.08 0.09 0.11) in the corner, the lit mesh
    // in the middle.
    EXPECT_EQ(ppmPixel(ppm, 1, 1), (std::array<int, 3>{20, 23, 28})) << shape;
    EXPECT_GT(ppmPixel(ppm, 48, 32)[0], 60) << shape;
  }
}

std::string slurp(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
}

TEST(VisualMeshClient, AMeshSceneIsDrawnFromItsOwnMeshAndItsRecordingWithThePen) {
  const test::TempDir dir("visual_mesh_scene");
  const std::string scene = std::string(THX_SOURCE_DIR) + "/scenes/brick_bowl.yaml";
  const std::string vc = std::string("LP_NUM_THREADS=2 ") + THX_VISUAL_CLIENT + " --scene " + scene;
  // The bowl from above its rim: the background in the corner, the lit bowl in the middle.
  const std::string shot = dir.file("bowl.ppm");
  ASSERT_EQ(std::system((vc + " --screenshot " + shot + " --size 96x64 --quiet").c_str()), 0);
  const std::string ppm = slurp(shot);
  EXPECT_EQ(ppmPixel(ppm, 1, 1), (std::array<int, 3>{20, 23, 28}));
  EXPECT_GT(ppmPixel(ppm, 48, 32)[0], 40);
  // A recording of the scene, two frames a second of its first 1.5 s: the pen hovers over the rim
  // and comes down, drawn beside the bowl.
  const std::string log = dir.file("bowl.lcm");
  const std::string hd = std::string(THX_HAPTICD) + " --scene " + scene + " --lockstep --no-lcm --no-mlock --quiet --duration 1.5 --record " +
                         log + " --flight-dir " + dir.file("") + " > /dev/null";
  ASSERT_EQ(std::system(hd.c_str()), 0) << hd;
  ASSERT_EQ(std::system((vc + " --replay-log " + log + " --rate 2 --format ppm --size 96x64 --out " + dir.file("frames") +
                         " --quiet").c_str()),
            0);
  const std::string first = slurp(dir.file("frames/frame_0000.ppm")), last = slurp(dir.file("frames/frame_0002.ppm"));
  ASSERT_FALSE(first.empty());
  ASSERT_FALSE(last.empty());
  EXPECT_NE(first, last);  // the pen moved
  // The same scene on another host with another bowl (64 segments around, not 128): same name, same
  // texture, another mesh, so the recording's fingerprint is not this scene's and the replay is refused.
  std::filesystem::create_directories(dir.file("other/paths"));
  std::filesystem::copy_file(std::string(THX_SOURCE_DIR) + "/scenes/paths/bowl_wall_half_circle.csv",
                             dir.file("other/paths/bowl_wall_half_circle.csv"));
  std::string text = slurp(scene);
  const std::size_t at = text.find("segments: 128");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, 13, "segments: 64 ");
  std::ofstream(dir.file("other/brick_bowl.yaml")) << text;
  const std::string other = std::string("LP_NUM_THREADS=2 ") + THX_VISUAL_CLIENT + " --scene " + dir.file("other/brick_bowl.yaml") +
                            " --replay-log " + log + " --rate 2 --format ppm --size 96x64 --out " + dir.file("other_frames") +
                            " --quiet 2> " + dir.file("other_err.txt");
  EXPECT_NE(std::system(other.c_str()), 0) << other;
  EXPECT_NE(slurp(dir.file("other_err.txt")).find("fingerprint"), std::string::npos) << slurp(dir.file("other_err.txt"));
  // --window and --live draw planes only.
  for (const char* mode : {"--window --window-frames 1", "--live --out " }) {
    const std::string cmd = vc + " " + mode + (std::string(mode).rfind("--live", 0) == 0 ? dir.file("live") : "") +
                            " --quiet 2> " + dir.file("err.txt");
    EXPECT_NE(std::system(cmd.c_str()), 0) << cmd;
    EXPECT_NE(slurp(dir.file("err.txt")).find("surface.mesh"), std::string::npos) << slurp(dir.file("err.txt"));
  }
}

}  // namespace
}  // namespace thx::visual::test_mesh_client
