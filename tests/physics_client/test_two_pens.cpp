// Several pens (issue 30): physics-client simulates a pen per hapticd device. The programs as a user
// runs them: hapticd records scenes/two_pens_two_balls.yaml in lock-step, physics-client replays
// the recording; each ball moves only once its own pen reaches it, along that pen's stroke. With
// the right device left out of the scene (a one-device variant), or --device N on the two-pen
// log, only that pen's ball moves. And in-process: each pen's force goes out as client_force_t
// for its own device.
#include <gtest/gtest.h>

#include <lcm/lcm-cpp.hpp>
#include <thx_msgs/log_reader.hpp>

#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "clients/physics_client/driver.hpp"
#include "clients/physics_client/lcm_io.hpp"
#include "clients/physics_client/physics_scene.hpp"
#include "scenes/scene_loader.hpp"
#include "tests/support/flat_json.hpp"
#include "tests/support/process.hpp"
#include "tests/support/temp_dir.hpp"
#include "thx_msgs/protocol.hpp"

namespace test_two_pens {

namespace {

using namespace thx::physclient;
using thx::test::jsonNumber;
using thx::test::shellStatus;
using thx::test::slurp;

const std::string kScene = std::string(THX_SOURCE_DIR) + "/scenes/two_pens_two_balls.yaml";
constexpr double kBallRadius = 0.006, kPenRadius = 0.004;  // the scene's balls, PenOptions' default
// A pen reaches a ball when its tip comes this close along the plane to the ball's resting centre:
// the two radii, and 0.5 mm for the hand's wobble across its stroke.
constexpr double kReach = kBallRadius + kPenRadius + 0.0005;
constexpr double kSettled_s = 0.25;  // the balls have dropped into their dimples (rest: 0.02 s)
constexpr double kStill_m = 5e-5;    // a ball no pen reached stays within 0.05 mm of where it settled
constexpr double kNever = std::numeric_limits<double>::infinity();

struct Point {
  double t_s;
  double x, y;
};
using Track = std::vector<Point>;

// Each device's tip along the plane (z = 0, identity pose), t from the session's first tick.
std::map<int, Track> penTracks(const std::string& session) {
  std::map<int, Track> out;
  std::int64_t first = -1;
  thx_msgs::forEachLogMessage<thx_msgs::device_state_t>(
      session, "THX_DEVICE_STATE", [&](const thx_msgs::device_state_t& s, const thx_msgs::LogPosition&) {
        if (first < 0) first = s.tick;
        out[s.device].push_back({double(s.tick - first) * 1e-3, s.p_world[0], s.p_world[1]});
      });
  return out;
}

// physics-client --poses-csv: each object's centre along the plane at every pose.
std::map<std::string, Track> ballTracks(const std::string& csv) {
  std::map<std::string, Track> out;
  std::ifstream in(csv);
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    std::istringstream row(line);
    std::string t, name, x, y;
    std::getline(row, t, ','), std::getline(row, name, ','), std::getline(row, x, ','), std::getline(row, y, ',');
    out[name.substr(1)].push_back({std::stod(t), std::stod(x), std::stod(y)});
  }
  return out;
}

Point at(const Track& track, double t_s) {
  for (const Point& p : track)
    if (p.t_s >= t_s) return p;
  return track.back();
}

// When `pen` first comes within kReach of `ball`'s settled centre (kNever: it never does).
double reachTime(const Track& pen, const Point& ball) {
  for (const Point& p : pen)
    if (std::hypot(p.x - ball.x, p.y - ball.y) <= kReach) return p.t_s;
  return kNever;
}

// When `ball` first lies more than `d_m` from where it settled (kNever: it never does).
double moveTime(const Track& ball, double d_m) {
  const Point rest = at(ball, kSettled_s);
  for (const Point& p : ball)
    if (p.t_s >= kSettled_s && std::hypot(p.x - rest.x, p.y - rest.y) > d_m) return p.t_s;
  return kNever;
}

class TwoPens : public ::testing::Test {
 protected:
  std::string path(const std::string& name) const { return dir_.file(name); }
  // hapticd records `scene` in lock-step to `session`.
  void record(const std::string& scene, const std::string& session) const {
    ASSERT_EQ(shellStatus(std::string(THX_HAPTICD) + " --scene " + scene + " --lockstep --no-lcm --no-mlock --quiet --record " +
                          session + " > " + path("hapticd.out") + " 2>&1"),
              0)
        << slurp(path("hapticd.out"));
  }
  // physics-client on `session` (options: --device N), its poses at every step; the summary JSON.
  std::string replay(const std::string& scene, const std::string& session, const std::string& options,
                     const std::string& name) const {
    const int rc = shellStatus(std::string(THX_PHYSICS_CLIENT) + " --scene " + scene + " --replay-log " + session + " " +
                               options + " --no-lcm --quiet --pose-rate 1000 --poses-csv " + path(name + ".csv") +
                               " --json " + path(name + ".json") + " > " + path(name + ".out") + " 2>&1");
    EXPECT_EQ(rc, 0) << slurp(path(name + ".out"));
    return slurp(path(name + ".json"));
  }
  thx::test::TempDir dir_{"thx_two_pens"};
};

// The settled centres, the pens' reach times and the balls' first 1 mm moves, printed.
void print(const char* run, const std::map<std::string, Track>& balls, double reach_left, double reach_right) {
  const Track& l = balls.at("left_ball");
  const Track& r = balls.at("right_ball");
  const Point l0 = at(l, kSettled_s), r0 = at(r, kSettled_s);
  std::printf("[measured] %s: left pen reaches its ball at %.3f s, the ball moves 1 mm by %.3f s, ends (%+.2f, %+.2f) mm "
              "from rest; right pen %.3f s, %.3f s, (%+.2f, %+.2f) mm\n",
              run, reach_left, moveTime(l, 1e-3), (l.back().x - l0.x) * 1e3, (l.back().y - l0.y) * 1e3, reach_right,
              moveTime(r, 1e-3), (r.back().x - r0.x) * 1e3, (r.back().y - r0.y) * 1e3);
}

TEST_F(TwoPens, EachPenPushesItsOwnBallAlongItsStroke) {
  record(kScene, path("two.lcm"));
  const std::string json = replay(kScene, path("two.lcm"), "", "two");
  const std::map<int, Track> pens = penTracks(path("two.lcm"));
  ASSERT_EQ(pens.size(), 2u);
  const std::map<std::string, Track> balls = ballTracks(path("two.csv"));
  const Track& left = balls.at("left_ball");
  const Track& right = balls.at("right_ball");
  const double reach_left = reachTime(pens.at(0), at(left, kSettled_s));
  const double reach_right = reachTime(pens.at(1), at(right, kSettled_s));
  print("two pens", balls, reach_left, reach_right);

  // Each pen reaches its own ball, the left one well before the right one (the scene's timing) and
  // never the other's.
  EXPECT_LT(reach_left, 2.0);
  EXPECT_GT(reach_right, reach_left + 1.0);
  EXPECT_LT(reach_right, 3.4);
  EXPECT_EQ(reachTime(pens.at(0), at(right, kSettled_s)), kNever);
  EXPECT_EQ(reachTime(pens.at(1), at(left, kSettled_s)), kNever);
  // A ball stays put until its pen reaches it, then moves within 0.1 s.
  EXPECT_GE(moveTime(left, kStill_m), reach_left);
  EXPECT_LE(moveTime(left, 1e-3), reach_left + 0.1);
  EXPECT_GE(moveTime(right, kStill_m), reach_right);
  EXPECT_LE(moveTime(right, 1e-3), reach_right + 0.1);
  // Each along its pen's stroke (left: +x, right: -x) by more than a dimple (12.5 mm), staying on
  // its row (within 2 mm across).
  const Point l0 = at(left, kSettled_s), r0 = at(right, kSettled_s);
  EXPECT_GT(left.back().x - l0.x, 0.0125);
  EXPECT_LT(std::fabs(left.back().y - l0.y), 0.002);
  EXPECT_LT(right.back().x - r0.x, -0.0125);
  EXPECT_LT(std::fabs(right.back().y - r0.y), 0.002);

  // Each pen felt its own ball: the summary's pens, device 0 then device 1.
  SCOPED_TRACE(json);
  const std::size_t pen0 = json.find("{\"device\": 0,"), pen1 = json.find("{\"device\": 1,");
  ASSERT_NE(pen0, std::string::npos);
  ASSERT_NE(pen1, std::string::npos);
  for (const std::size_t at : {pen0, pen1}) {
    EXPECT_GT(jsonNumber(json.substr(at), "contact_steps"), 20);  // measured 75 and 128: the ball runs ahead
    EXPECT_GT(jsonNumber(json.substr(at), "max_force_sent_n"), 0.01);
  }
  EXPECT_EQ(jsonNumber(json, "pen_contact_steps"),
            jsonNumber(json.substr(pen0), "contact_steps") + jsonNumber(json.substr(pen1), "contact_steps"));

  // --device N on the same log: that pen alone, so only its ball moves.
  for (const int device : {0, 1}) {
    const std::string name = "device" + std::to_string(device);
    const std::string one = replay(kScene, path("two.lcm"), "--device " + std::to_string(device), name);
    EXPECT_EQ(one.find("\"pens\""), std::string::npos) << one;  // one pen: the summary as before issue 30
    const std::map<std::string, Track> b = ballTracks(path(name + ".csv"));
    const Track& pushed = b.at(device == 0 ? "left_ball" : "right_ball");
    const Track& other = b.at(device == 0 ? "right_ball" : "left_ball");
    EXPECT_EQ(moveTime(other, kStill_m), kNever) << name;
    EXPECT_GT(std::fabs(pushed.back().x - at(pushed, kSettled_s).x), 0.0125) << name;
  }
}

// The scene with its right device left out: one pen, and only the left ball moves.
TEST_F(TwoPens, OnePenAloneMovesOnlyItsBall) {
  std::string text = slurp(kScene);
  const std::size_t right = text.find("  - name: right"), objects = text.find("\nobjects:");
  ASSERT_NE(right, std::string::npos);
  ASSERT_NE(objects, std::string::npos);
  text.erase(right, objects - right);
  const std::string scene = path("one_pen.yaml");
  std::ofstream(scene) << text;
  ASSERT_EQ(thx::scene::deviceCount(thx::scene::loadScene(scene)), 1u);

  record(scene, path("one.lcm"));
  const std::string json = replay(scene, path("one.lcm"), "", "one");
  EXPECT_EQ(json.find("\"pens\""), std::string::npos) << json;
  const std::map<std::string, Track> balls = ballTracks(path("one.csv"));
  const Track& left = balls.at("left_ball");
  const double reach_left = reachTime(penTracks(path("one.lcm")).at(0), at(left, kSettled_s));
  print("one pen", balls, reach_left, kNever);
  EXPECT_LT(reach_left, 2.0);
  EXPECT_GE(moveTime(left, kStill_m), reach_left);
  EXPECT_GT(left.back().x - at(left, kSettled_s).x, 0.0125);
  EXPECT_EQ(moveTime(balls.at("right_ball"), kStill_m), kNever);  // no pen of its own: never moves
}

// In-process: pen 1 pushes the right ball while pen 0 stays parked; every force LcmSink sends
// while it pushes is for device 1, and the releases name both devices once each.
TEST(TwoPensRouting, EachPensForceGoesToItsOwnDevice) {
  SimOptions so;
  so.pens = 2;
  PhysicsScene sim(thx::scene::loadScene(kScene), so);
  ASSERT_EQ(sim.penCount(), 2);
  lcm::LCM lcm("memq://");
  ASSERT_TRUE(lcm.good());
  std::map<int, int> forces, releases;  // per device
  struct Handler {
    std::map<int, int>* forces;
    std::map<int, int>* releases;
    void on(const lcm::ReceiveBuffer*, const std::string&, const thx_msgs::client_force_t* m) {
      const bool zero = m->f_world[0] == 0 && m->f_world[1] == 0 && m->f_world[2] == 0;
      ++(*(zero ? releases : forces))[m->device];
    }
  } handler{&forces, &releases};
  lcm.subscribe(thx_msgs::kChannelClientForce, &Handler::on, &handler);
  LcmSinkOptions options;
  options.devices = {0, 1};
  LcmSink sink(lcm, options);
  DriverOptions d;
  d.pose_hz = d.contact_hz = 0;
  Driver driver(sim, sink, d);
  // The right ball rests at (0.03125, 0.05625); pen 1 comes from +x along its row at 5 cm/s.
  for (int k = 0; k < 600; ++k) {
    const double x = 0.05 - 0.05 * std::max(0.0, (k - 200) * 1e-3);
    driver.step({Driver::PenInput{}, Driver::PenInput{Eigen::Vector3d(x, 0.05625, 0.0), k, std::nullopt}});
    while (lcm.handleTimeout(0) > 0) {
    }
  }
  sink.releaseAll(sim);
  while (lcm.handleTimeout(0) > 0) {
  }
  EXPECT_GT(forces[1], 50);
  EXPECT_EQ(forces.count(0), 0u);
  EXPECT_EQ(releases[0], 1);
  EXPECT_GE(releases[1], 1);  // releaseAll's, and the driver's if the push ended before
  EXPECT_LT(sim.body(1).p_world.x(), 0.03125 - 0.005);  // pushed along -x
  EXPECT_NEAR(sim.body(0).p_world.x(), -0.03125, 1e-4);  // the left ball: no pen came
}

}  // namespace

}  // namespace test_two_pens
