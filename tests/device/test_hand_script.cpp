// HandScript: timeline and durations, smoothness (no jumps on a fine grid), frames, the path
// step, step validation, and the path CSV loader with each of its error messages.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <unistd.h>

#include "device/hand_script.hpp"

namespace test_hand_script {

using namespace thx::dev;

namespace {

constexpr double kEps = 1e-12;

HandScript exampleScript() {
  return HandScript({HandHold{0.5}, HandStroke{{-0.05, 0.0}, {0.05, 0.0}, 0.05, 1.0}, HandPress{{0.0, 0.01}, 1.5, 1.0}});
}

// A file under the test temp dir, removed by the fixture.
class CsvFile {
 public:
  CsvFile(const std::string& name, const std::string& text)
      : path_(std::filesystem::path(::testing::TempDir()) /
              ("thx_hand_path_" + std::to_string(::getpid()) + "_" + name + ".csv")) {
    std::ofstream(path_) << text;
  }
  ~CsvFile() { std::filesystem::remove(path_); }
  std::string path() const { return path_.string(); }

 private:
  std::filesystem::path path_;
};

// Loads the CSV and returns the error message (fails the test if it loads).
std::string csvError(const std::string& name, const std::string& text, int expect_line, const std::string& expect_field) {
  CsvFile f(name, text);
  try {
    HandScript::loadPathCsv(f.path());
  } catch (const HandScriptError& e) {
    EXPECT_EQ(e.file(), f.path());
    EXPECT_EQ(e.line(), expect_line) << e.what();
    EXPECT_EQ(e.field(), expect_field) << e.what();
    const std::string msg = e.what();
    EXPECT_EQ(msg.rfind(f.path() + (expect_line > 0 ? ":" + std::to_string(expect_line) + ": " : ": "), 0), 0u) << msg;
    return msg;
  }
  ADD_FAILURE() << "no error for " << name;
  return {};
}

}  // namespace

TEST(HandScript, EmptyScriptHoversAboveTheOrigin) {
  const HandScript s;
  EXPECT_EQ(s.duration(), 0.0);
  for (double t : {-1.0, 0.0, 3.0}) {
    const HandTarget h = s.sampleLocal(t);
    EXPECT_TRUE(h.p_m.isApprox(Eigen::Vector3d(0, 0, s.options().hover_height_m)));
    EXPECT_EQ(h.v_m_per_s, Eigen::Vector3d::Zero());
    EXPECT_EQ(h.push_n, Eigen::Vector3d::Zero());
    EXPECT_FALSE(h.pressing);
  }
}

TEST(HandScript, DurationsAddUp) {
  const HandScript s = exampleScript();
  const HandScriptOptions o;
  const double hold = 0.5;
  // The script starts hovering above the stroke's start: no transit before it.
  const double stroke = o.approach_s + o.force_ramp_s + (0.1 / 0.05 + o.stroke_ramp_s) + o.force_ramp_s + o.approach_s;
  const double hop_m = std::hypot(0.05, 0.01);
  const double press = std::max(hop_m / o.transit_speed_m_per_s, o.min_transit_s) + o.approach_s + o.force_ramp_s +
                       1.0 + o.force_ramp_s + o.approach_s;
  EXPECT_NEAR(s.duration(), hold + stroke + press, kEps);

  // A short stroke (shorter than its ramps) lasts 2 * length / speed.
  const HandScript short_stroke({HandStroke{{0, 0}, {0.001, 0}, 0.1, 1.0}});
  EXPECT_NEAR(short_stroke.duration(), 2 * o.approach_s + 2 * o.force_ramp_s + 2 * 0.001 / 0.1, kEps);
}

TEST(HandScript, SamplingIsContinuousOnAFineGrid) {
  const HandScript s = exampleScript();
  const double dt = 1e-4;
  const double force_rate_bound = 1.875 * 1.5 / s.options().force_ramp_s;  // min-jerk peak slope
  HandTarget prev = s.sampleLocal(-dt);
  double max_speed = 0.0;
  for (double t = 0.0; t < s.duration() + 0.5; t += dt) {
    const HandTarget h = s.sampleLocal(t);
    const double speed = (h.p_m - prev.p_m).norm() / dt;
    max_speed = std::max(max_speed, speed);
    ASSERT_LT(speed, 0.25) << "position jump at t = " << t;
    ASSERT_LT(std::abs(h.push_n.z() - prev.push_n.z()) / dt, force_rate_bound * 1.01) << "force jump at t = " << t;
    // The reported velocity is the derivative of the position (all moves here are C1).
    const HandTarget ahead = s.sampleLocal(t + dt);
    ASSERT_LT(((ahead.p_m - prev.p_m) / (2 * dt) - h.v_m_per_s).norm(), 2e-3) << "velocity mismatch at t = " << t;
    prev = h;
  }
  EXPECT_GT(max_speed, 0.05);  // the grid did see the moves
}

TEST(HandScript, PressHoversDescendsPushesAndLifts) {
  const HandScriptOptions o;
  const HandScript s({HandPress{{0.02, -0.01}, 2.0, 1.0}});
  const double contact_start = o.approach_s + o.force_ramp_s;
  EXPECT_NEAR(s.sampleLocal(0.0).p_m.z(), o.hover_height_m, kEps);
  EXPECT_FALSE(s.sampleLocal(0.0).pressing);
  const HandTarget mid = s.sampleLocal(contact_start + 0.5);
  EXPECT_TRUE(mid.p_m.isApprox(Eigen::Vector3d(0.02, -0.01, 0.0)));
  EXPECT_NEAR(mid.push_n.z(), -2.0, kEps);
  EXPECT_TRUE(mid.pressing);
  // Half way through the ramp the min-jerk force is exactly half.
  EXPECT_NEAR(s.sampleLocal(o.approach_s + 0.5 * o.force_ramp_s).push_n.z(), -1.0, 1e-12);
  // After the end: hover above the last point, no push, at rest.
  const HandTarget after = s.sampleLocal(s.duration() + 1.0);
  EXPECT_TRUE(after.p_m.isApprox(Eigen::Vector3d(0.02, -0.01, o.hover_height_m)));
  EXPECT_EQ(after.push_n, Eigen::Vector3d::Zero());
  EXPECT_EQ(after.v_m_per_s, Eigen::Vector3d::Zero());
}

TEST(HandScript, StrokeCruisesAtItsSpeed) {
  const HandScriptOptions o;
  const HandScript s({HandStroke{{0.0, 0.0}, {0.03, 0.04}, 0.05, 1.0}});  // 0.05 m long: 1 s + ramp
  const double body_start = o.approach_s + o.force_ramp_s;
  const Eigen::Vector3d dir(0.6, 0.8, 0.0);
  // Half way through the stroke's body (1.1 s) the target is half way along it, at full speed.
  const HandTarget cruise = s.sampleLocal(body_start + 0.55);
  EXPECT_TRUE(cruise.v_m_per_s.isApprox(0.05 * dir, 1e-12));
  EXPECT_TRUE(cruise.p_m.isApprox(0.025 * dir, 1e-12));
  EXPECT_TRUE(s.sampleLocal(body_start + 1.1).p_m.isApprox(0.05 * dir, 1e-12));
  EXPECT_NEAR(s.sampleLocal(body_start).v_m_per_s.norm(), 0.0, kEps);
}

TEST(HandScript, WorldSamplesFollowThePlane) {
  Eigen::Isometry3d plane = Eigen::Isometry3d::Identity();
  plane.linear() = Eigen::AngleAxisd(std::numbers::pi / 6, Eigen::Vector3d::UnitX()).toRotationMatrix();
  plane.translation() = Eigen::Vector3d(0.01, 0.02, -0.03);
  const HandScript s({HandPress{{0.01, 0.0}, 1.0, 1.0}});
  const double t = s.options().approach_s + s.options().force_ramp_s + 0.5;
  const HandTarget w = s.sample(t, plane);
  const Eigen::Vector3d n = plane.linear().col(2);
  EXPECT_TRUE(w.p_m.isApprox(plane * Eigen::Vector3d(0.01, 0.0, 0.0)));
  EXPECT_TRUE(w.push_n.isApprox(-1.0 * n));
  EXPECT_TRUE(w.pressing);
}

TEST(HandScript, PathStepInterpolatesItsSamples) {
  HandPath path;
  path.samples = {{0.0, {0.0, 0.0}, 1.0}, {0.5, {0.01, 0.0}, 2.0}, {1.0, {0.01, 0.01}, 2.0}};
  const HandScriptOptions o;
  const HandScript s({path});
  EXPECT_NEAR(s.duration(), 2 * o.approach_s + 2 * o.force_ramp_s + 1.0, kEps);
  const double t0 = o.approach_s + o.force_ramp_s;
  const HandTarget a = s.sampleLocal(t0 + 0.25);
  EXPECT_TRUE(a.p_m.isApprox(Eigen::Vector3d(0.005, 0.0, 0.0)));
  EXPECT_TRUE(a.v_m_per_s.isApprox(Eigen::Vector3d(0.02, 0.0, 0.0)));
  EXPECT_NEAR(a.push_n.z(), -1.5, kEps);
  EXPECT_TRUE(s.sampleLocal(t0 + 1.0).p_m.isApprox(Eigen::Vector3d(0.01, 0.01, 0.0)));
  // Ends lifted above the last sample.
  EXPECT_TRUE(s.sampleLocal(s.duration()).p_m.isApprox(Eigen::Vector3d(0.01, 0.01, o.hover_height_m)));
}

TEST(HandScript, IsDeterministic) {
  const HandScript a = exampleScript(), b = exampleScript();
  for (double t = 0.0; t < a.duration(); t += 0.0137) {
    EXPECT_EQ(a.sampleLocal(t).p_m, b.sampleLocal(t).p_m);
    EXPECT_EQ(a.sampleLocal(t).push_n, b.sampleLocal(t).push_n);
  }
}

// A move lifts the hand off the surface and pushes any way: the target goes to the point, the push
// to the move's with the same minimum-jerk weight; a hold keeps both; the next move starts from
// them; a contact step's transit ramps the push out; a script ending with a push ramps it out.
TEST(HandScript, MovesGoAnywhereWithTheirPushAndRampItOut) {
  const HandScriptOptions o;
  const Eigen::Vector3d grip(0.01, 0.0, 0.02), lift(0.01, 0.0, 0.05), side(-1.5, 0.0, 0.0);
  const HandScript s({HandMove{grip, side, 1.0}, HandHold{0.5}, HandMove{lift, side, 2.0}, HandPress{{0.0, 0.0}, 1.0, 0.5},
                      HandMove{lift, side, 1.0}});
  // Starts hovering above the first move's point.
  EXPECT_TRUE(s.sampleLocal(0.0).p_m.isApprox(Eigen::Vector3d(0.01, 0.0, o.hover_height_m)));
  // Half way through the first move: half way there, half the push (min-jerk weight 1/2 at 1/2).
  const HandTarget half = s.sampleLocal(0.5);
  EXPECT_NEAR((half.p_m - 0.5 * (Eigen::Vector3d(0.01, 0.0, o.hover_height_m) + grip)).norm(), 0.0, kEps);
  EXPECT_NEAR((half.push_n - 0.5 * side).norm(), 0.0, kEps);
  EXPECT_TRUE(half.pressing);
  // The hold keeps the point and the push; the second move lifts with it.
  const HandTarget held = s.sampleLocal(1.25);
  EXPECT_NEAR((held.p_m - grip).norm(), 0.0, kEps);
  EXPECT_EQ(held.push_n, side);
  EXPECT_EQ(held.v_m_per_s, Eigen::Vector3d::Zero());
  const HandTarget lifted = s.sampleLocal(3.5);
  EXPECT_NEAR((lifted.p_m - lift).norm(), 0.0, kEps);
  EXPECT_EQ(lifted.push_n, side);
  // The press's transit (from the lift to above its point) ramps the push out and descends as usual.
  const double hop = (Eigen::Vector3d(0.0, 0.0, o.hover_height_m) - lift).norm();
  const double transit = std::max({hop / o.transit_speed_m_per_s, o.min_transit_s, o.force_ramp_s});
  const HandTarget pressing = s.sampleLocal(3.5 + transit + o.approach_s + o.force_ramp_s + 0.25);
  EXPECT_NEAR((pressing.p_m - Eigen::Vector3d::Zero()).norm(), 0.0, kEps);
  EXPECT_NEAR((pressing.push_n - Eigen::Vector3d(0, 0, -1.0)).norm(), 0.0, kEps);
  // The last move ends pushing: ramped out over force_ramp_s, then at rest without a push.
  EXPECT_EQ(s.sampleLocal(s.duration() - 1e-9).push_n.x() < 0.0, true);
  const HandTarget after = s.sampleLocal(s.duration() + 1.0);
  EXPECT_NEAR((after.p_m - lift).norm(), 0.0, kEps);
  EXPECT_EQ(after.push_n, Eigen::Vector3d::Zero());
  EXPECT_FALSE(after.pressing);
  // No step in the position or the push anywhere (the push's rate bounded by the min-jerk slope).
  const double dt = 1e-4, rate_bound = 1.875 * 1.5 / o.force_ramp_s;
  HandTarget prev = s.sampleLocal(0.0);
  for (double t = dt; t < s.duration() + 0.2; t += dt) {
    const HandTarget h = s.sampleLocal(t);
    ASSERT_LT((h.p_m - prev.p_m).norm() / dt, 0.3) << "position jump at t = " << t;
    ASSERT_LT((h.push_n - prev.push_n).norm() / dt, rate_bound * 1.01) << "push jump at t = " << t;
    prev = h;
  }
}

TEST(HandScript, InvalidStepsAreRejectedWithTheirField) {
  const auto message = [](std::vector<HandStep> steps) {
    try {
      HandScript s(std::move(steps));
    } catch (const HandScriptError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message({HandHold{1.0}, HandStroke{{0, 0}, {0.1, 0}, -1.0, 1.0}}),
            "hand script step 2 (stroke): speed_m_per_s: out of range; expected a speed > 0 m/s, got '-1'");
  EXPECT_EQ(message({HandStroke{{0, 0}, {0, 0}, 0.1, 1.0}}),
            "hand script step 1 (stroke): to_m: equals from_m; expected a stroke of non-zero length, got '[0, 0]'");
  EXPECT_EQ(message({HandPress{{0, 0}, 1.0, 0.0}}),
            "hand script step 1 (press): duration_s: out of range; expected a duration > 0 s, got '0'");
  EXPECT_EQ(message({HandPress{{0, 0}, std::nan(""), 1.0}}),
            "hand script step 1 (press): force_n: not finite; expected a force >= 0 N, got 'nan'");
  EXPECT_EQ(message({HandMove{{0, 0, std::nan("")}, {0, 0, 0}, 1.0}}),
            "hand script step 1 (move): to_m: not finite; expected finite [x, y, z] in m, got '[0, 0, nan]'");
  EXPECT_EQ(message({HandHold{1.0}, HandMove{{0, 0, 0.01}, {0, 0, 0}, 0.0}}),
            "hand script step 2 (move): duration_s: out of range; expected a duration > 0 s, got '0'");
  HandPath backwards{{{0.0, {0, 0}, 1.0}, {0.0, {0, 0}, 1.0}}, "p.csv"};
  EXPECT_EQ(message({backwards}),
            "hand script step 1 (path from p.csv): samples[1].t_s: time does not increase; expected a time > 0 s, got '0'");
}

TEST(HandPathCsv, LoadsHeaderCommentsAndBlankLines) {
  CsvFile f("good",
            "# a recorded circle\n"
            "t_s, x_m, y_m, force_n\n"
            "\n"
            "0.0, 0.01, 0.0, 1.0   # start\n"
            "  0.1 ,0.0,+0.01,1.5\r\n"
            "0.2, -0.01, 0, 2e-1\n");
  const HandPath p = HandScript::loadPathCsv(f.path());
  ASSERT_EQ(p.samples.size(), 3u);
  EXPECT_EQ(p.source, f.path());
  EXPECT_EQ(p.samples[1].t_s, 0.1);
  EXPECT_EQ(p.samples[1].p_m, Eigen::Vector2d(0.0, 0.01));
  EXPECT_EQ(p.samples[1].force_n, 1.5);
  EXPECT_EQ(p.samples[2].force_n, 0.2);
  // Without a header too.
  CsvFile g("noheader", "0,0,0,1\n1,0.01,0,1\n");
  EXPECT_EQ(HandScript::loadPathCsv(g.path()).samples.size(), 2u);
}

TEST(HandPathCsv, EachErrorNamesFileLineAndField) {
  EXPECT_NE(csvError("header", "time, x, y, f\n0,0,0,1\n1,0,0,1\n", 1, "header")
                .find("not a header or a data row; expected the header 't_s, x_m, y_m, force_n' or numbers, got 'time, x, y, f'"),
            std::string::npos);
  EXPECT_NE(csvError("fields", "0,0,0,1\n1,0,0\n", 2, "row").find("wrong number of fields; expected 4 fields t_s, x_m, y_m, force_n, got '3 fields'"),
            std::string::npos);
  EXPECT_NE(csvError("nan_number", "# c\n0,0,0,1\n1,abc,0,1\n", 3, "x_m").find("x_m: not a number; expected a position in m, got 'abc'"),
            std::string::npos);
  EXPECT_NE(csvError("inf", "0,0,0,1\n1,0,inf,1\n", 2, "y_m").find("y_m: not finite; expected a position in m, got 'inf'"),
            std::string::npos);
  EXPECT_NE(csvError("negative_time", "-0.1,0,0,1\n1,0,0,1\n", 1, "t_s").find("t_s: out of range; expected a time >= 0 s, got '-0.1'"),
            std::string::npos);
  EXPECT_NE(csvError("backwards", "0,0,0,1\n0.5,0,0,1\n0.5,0,0,1\n", 3, "t_s")
                .find("t_s: time does not increase; expected a time > 0.5 s (the previous row's), got '0.5'"),
            std::string::npos);
  EXPECT_NE(csvError("negative_force", "0,0,0,1\n1,0,0,-2\n", 2, "force_n").find("force_n: out of range; expected a force >= 0 N, got '-2'"),
            std::string::npos);
  EXPECT_NE(csvError("late_header", "0,0,0,1\nt_s,x_m,y_m,force_n\n", 2, "t_s").find("t_s: not a number"), std::string::npos);
  EXPECT_NE(csvError("one_row", "t_s,x_m,y_m,force_n\n0,0,0,1\n", 0, "samples")
                .find(": samples: too few samples; expected at least 2 rows t_s, x_m, y_m, force_n, got 1"),
            std::string::npos);
  EXPECT_NE(csvError("empty", "# nothing\n\n", 0, "samples").find("got 0"), std::string::npos);

  const std::string missing = (std::filesystem::path(::testing::TempDir()) / "thx_no_such_path.csv").string();
  try {
    HandScript::loadPathCsv(missing);
    ADD_FAILURE() << "no error for a missing file";
  } catch (const HandScriptError& e) {
    EXPECT_EQ(std::string(e.what()),
              missing + ": cannot open the path file; expected a readable CSV file with rows t_s, x_m, y_m, force_n");
  }
}

TEST(HandPathCsv, LoadedPathDrivesAScript) {
  CsvFile f("script", "t_s,x_m,y_m,force_n\n0,0,0,1\n0.5,0.02,0,1\n");
  const HandScript s({HandHold{0.2}, HandScript::loadPathCsv(f.path())});
  const HandScriptOptions o;
  EXPECT_NEAR(s.duration(), 0.2 + 2 * o.approach_s + 2 * o.force_ramp_s + 0.5, kEps);
  EXPECT_TRUE(s.sampleLocal(0.2 + o.approach_s + o.force_ramp_s + 0.25).p_m.isApprox(Eigen::Vector3d(0.01, 0, 0)));
}

}  // namespace test_hand_script
