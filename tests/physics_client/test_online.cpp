// The online path of issue 6, as `make demo` runs it: hapticd (real time, the simulated hand
// stroking the pen) and physics-client subscribed to it over LCM udpm (ttl=0, a port of this
// test's own), on the demo scene. Checked here is what connects: physics-client receives
// hapticd's device states and steps on them, publishes, and hapticd accepts physics-client's
// client forces (at least the release it sends when it stops). Whether the pen reaches the ball
// depends on how the two processes interleave on the machine (a clean-clone `make test` once saw
// 2 contact steps in the sanitizer tree), so it is not asserted; the push itself is
// test_push.cpp (offline, deterministic), a client force through the safety stage is
// tests/server/test_servo.cpp (lock-step), and the demo shows the whole. Skipped when udpm is
// not available (no multicast route).
#include <string>

#include "tests/support/hapticd_harness.hpp"

namespace test_online {

namespace {

using namespace thx::test;

class PhysicsClientOnline : public HapticdProcessTest {};

}  // namespace

TEST_F(PhysicsClientOnline, PhysicsClientFollowsTheDeviceAndHapticdTakesItsForces) {
  if (!udpmAvailable()) GTEST_SKIP() << "LCM udpm is not available here (" << url_ << "): no multicast route";
  const std::string scene = "scenes/pen_pushes_ball_dimples.yaml";
  // hapticd runs until stopped (--duration 0), so it is still there when physics-client sends the
  // release on its way out.
  server_ = spawn({THX_HAPTICD, "--scene", scene, "--duration", "0", "--no-mlock", "--lcm-url", url_, "--stats-json",
                   path("s.json"), "--flight-dir", path(""), "--quiet"},
                  path("hd.out"), path("hd.err"));
  const pid_t physics = spawn({THX_PHYSICS_CLIENT, "--scene", scene, "--duration", "3", "--lcm-url", url_,
                               "--connect-timeout", "30", "--json", path("pc.json"), "--quiet"},
                              path("pc.out"), path("pc.err"));
  children_.push_back(physics);
  EXPECT_EQ(reap(physics, 120), 0) << slurp(path("pc.err"));
  children_.clear();
  EXPECT_EQ(stopServer(), 0) << serverLog();

  const std::string pc = slurp(path("pc.json")), hd = slurp(path("s.json"));
  SCOPED_TRACE("physics-client --json: " + pc + "\nhapticd --stats-json: " + hd);
  EXPECT_EQ(jsonNumber(pc, "steps"), 3000);            // --duration 3 at the scene's 1 kHz, on the kit's pacer
  EXPECT_GT(jsonNumber(pc, "device_states"), 0);       // it heard hapticd
  EXPECT_GT(jsonNumber(pc, "pose_reports"), 0);        // and published
  EXPECT_GE(jsonNumber(pc, "forces_sent"), 1);         // the release at exit, and any contact force
  EXPECT_GE(jsonNumber(hd, "client_forces_accepted"), 1);  // hapticd took them from the network
  EXPECT_LE(jsonNumber(pc, "max_force_sent_n"), 2.0 + 1e-9);  // --max-force default
  const double f = jsonNumber(hd, "max_force_n");
  EXPECT_TRUE(std::isfinite(f));
  EXPECT_LE(f, 7.9 + 1e-9);  // the device's peak: the safety stage held
}

}  // namespace test_online
