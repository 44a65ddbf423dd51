// physics-client's options and pen-path files: clear errors naming the option or FILE:LINE.
#include <gtest/gtest.h>

#include "clients/physics_client/options.hpp"
#include "clients/physics_client/pen_path.hpp"

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

  EXPECT_NE(usageError({}).find("--scene FILE is required"), std::string::npos);
  EXPECT_NE(usageError({"--scene", "s", "--rate", "abc"}).find("--rate: expected a number"), std::string::npos);
  EXPECT_NE(usageError({"--scene", "s", "--rate", "nan"}).find("got 'nan'"), std::string::npos);
  EXPECT_NE(usageError({"--scene", "s", "--max-force", "-1"}).find("--max-force"), std::string::npos);
  EXPECT_NE(usageError({"--scene", "s", "--pen-shape", "cube"}).find("capsule, sphere or none"), std::string::npos);
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

}  // namespace
