// physics-client's options and pen-path files: clear errors naming the option or FILE:LINE.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "clients/physics_client/driver.hpp"
#include "clients/physics_client/options.hpp"
#include "clients/physics_client/pen_path.hpp"
#include "clients/physics_client/pose_csv.hpp"
#include "scenes/scene_loader.hpp"

namespace test_cli {

namespace {

using namespace thx::physclient;

std::string usageError(const std::vector<std::string>& args) {
  try {
    parseOptions(args);
  } catch (const UsageError& e) {
    return e.what();
  }
  return "(no error)";
}

std::string pathError(const std::string& text) {
  try {
    parsePenCsv(text, "p.csv");
  } catch (const PenPathError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(PhysicsClientCli, Options) {
  const Options o = parseOptions({"--scene", "s.yaml", "--rate", "500", "--pen-csv", "p.csv", "--max-force", "1.5",
                                  "--pen-shape", "sphere", "--no-lcm"});
  EXPECT_EQ(o.scene, "s.yaml");
  EXPECT_EQ(*o.rate_hz, 500.0);
  EXPECT_EQ(o.pen_source, PenSource::Csv);
  EXPECT_EQ(o.pen.max_force_n, 1.5);
  EXPECT_EQ(o.pen.shape, PenShape::Sphere);
  EXPECT_TRUE(parseOptions({"--help"}).help);
  EXPECT_EQ(parseOptions({"--scene", "s", "--no-pen", "--duration", "1", "--poses-csv", "p.csv"}).poses_csv, "p.csv");
  EXPECT_NE(usageError({"--scene", "s", "--poses-csv"}).find("--poses-csv: missing value"), std::string::npos);

  EXPECT_NE(usageError({}).find("--scene FILE|NAME is required"), std::string::npos);
  EXPECT_NE(usageError({"--scene", "s", "--rate", "abc"}).find("--rate: expected a number"), std::string::npos);
  EXPECT_NE(usageError({"--scene", "s", "--rate", "nan"}).find("got 'nan'"), std::string::npos);
  EXPECT_NE(usageError({"--scene", "s", "--max-force", "-1"}).find("--max-force"), std::string::npos);
  EXPECT_NE(usageError({"--scene", "s", "--pen-shape", "cube"}).find("capsule, sphere or none"), std::string::npos);
  const Options grasp = parseOptions({"--scene", "s", "--pen-coupling", "300", "--pen-mass", "0.03", "--pen-friction", "0.9"});
  EXPECT_EQ(grasp.pen.coupling_n_per_m, 300.0);
  EXPECT_TRUE(grasp.pen.coupled());
  EXPECT_EQ(grasp.pen.coupling_mass_kg, 0.03);
  EXPECT_EQ(grasp.pen.material_friction, 0.9);
  EXPECT_FALSE(parseOptions({"--scene", "s"}).pen.coupled());  // kinematic pens by default
  EXPECT_NE(usageError({"--scene", "s", "--pen-coupling", "-5"}).find("--pen-coupling"), std::string::npos);
  EXPECT_NE(usageError({"--scene", "s", "--pen-mass", "0"}).find("--pen-mass"), std::string::npos);
  EXPECT_NE(usageError({"--scene", "s", "--pen-csv", "a", "--pen-script"}).find("exclude each other"), std::string::npos);
  EXPECT_NE(usageError({"--scene", "s", "--no-lcm"}).find("offline pen"), std::string::npos);
  EXPECT_NE(usageError({"--scene", "s", "--no-pen"}).find("--duration"), std::string::npos);
  EXPECT_NE(usageError({"--scene", "s", "--client-id", "a b"}).find("[A-Za-z0-9_-]"), std::string::npos);
  EXPECT_NE(usageError({"--scene"}).find("--scene: missing value"), std::string::npos);
  EXPECT_NE(usageError({"--scene", "s", "--bogus"}).find("unknown option '--bogus'"), std::string::npos);
}

TEST(PhysicsClientCli, PenCsv) {
  const auto s = parsePenCsv("# comment\nt_s, x_m, y_m, z_m\n0, 0, 0, 0\n\n1, 0.1, 0, 0 # end\n", "p.csv");
  ASSERT_EQ(s.size(), 2u);
  const PenPath path(s);
  EXPECT_NEAR(path.at(0.5).x(), 0.05, 1e-12);
  EXPECT_NEAR(path.at(5.0).x(), 0.1, 1e-12);

  EXPECT_NE(pathError("0, 0, 0, 0\n0, 1, 0, 0\n").find("p.csv:2: t_s: time not increasing"), std::string::npos);
  EXPECT_NE(pathError("0, 0, 0, 0\n1, x, 0, 0\n").find("p.csv:2: x_m: not a number"), std::string::npos);
  EXPECT_NE(pathError("0, 0, 0, 0\n1, 0, inf, 0\n").find("p.csv:2: y_m: not a finite number"), std::string::npos);
  EXPECT_NE(pathError("0, 0, 0\n").find("p.csv:1: row: wrong number of values"), std::string::npos);
  EXPECT_NE(pathError("t_s, x, y, z\n").find("p.csv:1: header"), std::string::npos);
  EXPECT_NE(pathError("0, 0, 0, 0\n").find("too few samples"), std::string::npos);
  EXPECT_NE(pathError("-1, 0, 0, 0\n0, 0, 0, 0\n").find("negative time"), std::string::npos);
  try {
    loadPenCsv("/nonexistent/p.csv");
    FAIL();
  } catch (const PenPathError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/p.csv: cannot open"), std::string::npos);
  }
}

// --poses-csv: a header, then one row per moving object per pose report, in the world and on the
// surface (fixed obstacles are left out); an unwritable file is an error naming it.
TEST(PhysicsClientCli, PosesCsv) {
  thx::scene::Scene scene = thx::scene::loadScene(std::string(THX_SOURCE_DIR) + "/scenes/zigzag_street.yaml");
  scene.surface.texture.generator.size = 64;
  PhysicsScene sim(scene, SimOptions{});
  const std::string file = (std::filesystem::temp_directory_path() / "thx_pc_poses.csv").string();
  std::int64_t reports = 0;
  {
    PoseCsvSink csv(file);
    DriverOptions d;
    d.pose_hz = 100.0;
    Driver driver(sim, csv, d);
    for (int k = 0; k < 100; ++k) driver.step(std::nullopt);
    reports = driver.summary().pose_reports;  // the first step, then every 10 ms: 11
  }
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "t_s, object, x_m, y_m, z_m, x_local_m, y_local_m, h_local_m, speed_m_per_s, spin_rad_per_s");
  int rows = 0, kerb = 0;
  while (std::getline(in, line)) {
    ++rows;
    kerb += line.find(", kerb,") != std::string::npos;
  }
  EXPECT_EQ(reports, 11);
  EXPECT_EQ(rows, 3 * reports);  // the three balls each time
  EXPECT_EQ(kerb, 0);
  try {
    PoseCsvSink bad("/nonexistent/p.csv");
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/p.csv: cannot write the poses"), std::string::npos);
  }
}

}  // namespace

// Scene names (--scene NAME, and the scenes hapticd switches to) are found in --scenes-dir; without
// it, beside the --scene file, or in scenes/ for a name.
TEST(PhysicsClientCli, ScenesDirDefaultsToTheSceneFilesFolder) {
  EXPECT_EQ(parseOptions({"--scene", "lab/scenes/vvalley.yaml"}).scenesDir(), "lab/scenes");
  EXPECT_EQ(parseOptions({"--scene", "/srv/scenes/vvalley.yaml"}).scenesDir(), "/srv/scenes");
  EXPECT_EQ(parseOptions({"--scene", "vvalley.yaml"}).scenesDir(), ".");
  EXPECT_EQ(parseOptions({"--scene", "vvalley"}).scenesDir(), "scenes");
  EXPECT_EQ(parseOptions({"--scene", "lab/vvalley.yaml", "--scenes-dir", "other"}).scenesDir(), "other");
  EXPECT_EQ(parseOptions({"--scene", "vvalley", "--scenes-dir", "other"}).scenesDir(), "other");
}

}  // namespace test_cli
