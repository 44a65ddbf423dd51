// The online path of issue 6, as `make demo` runs it: hapticd (real time, the simulated hand
// stroking the pen) and physics-client subscribed to it over LCM udpm (ttl=0, a port of this
// test's own), on the demo scene. The pen follows the device, touches the ball and pushes it;
// its contact force goes back to hapticd, which applies it on the pen through its safety stage.
// Counts only, with wide margins: how the two processes interleave depends on the machine.
// Skipped when udpm is not available (no multicast route).
#include <string>

#include "tests/support/hapticd_harness.hpp"

namespace {

using namespace thx::test;

class PhysicsClientOnline : public HapticdProcessTest {};

// "name": "ball" ... "displacement_m": X in physics-client's --json.
double displacementOf(const std::string& json, const std::string& object) {
  const auto at = json.find("{\"name\": \"" + object + "\"");
  return at == std::string::npos ? NAN : jsonNumber(json.substr(at), "displacement_m");
}

}  // namespace

TEST_F(PhysicsClientOnline, ThePenPushesTheBallAndFeelsThePush) {
  if (!udpmAvailable()) GTEST_SKIP() << "LCM udpm is not available here (" << url_ << "): no multicast route";
  const std::string scene = "scenes/pen_pushes_ball_dimples.yaml";
  const pid_t physics = spawn({THX_PHYSICS_CLIENT, "--scene", scene, "--duration", "5.5", "--lcm-url", url_,
                               "--connect-timeout", "30", "--json", path("pc.json"), "--quiet"},
                              path("pc.out"), path("pc.err"));
  children_.push_back(physics);
  // hapticd runs the scene's hand script to its end (about 5 s), then stops by itself.
  server_ = spawn({THX_HAPTICD, "--scene", scene, "--no-mlock", "--lcm-url", url_, "--stats-json", path("s.json"),
                   "--flight-dir", path(""), "--quiet"},
                  path("hd.out"), path("hd.err"));
  EXPECT_EQ(reap(server_, 120), 0) << serverLog();
  server_ = -1;
  EXPECT_EQ(reap(physics, 120), 0) << slurp(path("pc.err"));
  children_.clear();

  const std::string pc = slurp(path("pc.json")), hd = slurp(path("s.json"));
  SCOPED_TRACE("physics-client --json: " + pc + "\nhapticd --stats-json: " + hd);
  EXPECT_GT(jsonNumber(pc, "steps"), 1000);              // it ran online, stepping on its own clock
  EXPECT_GT(jsonNumber(pc, "pen_contact_steps"), 5);     // the pen (following the device) touched the ball
  EXPECT_GT(jsonNumber(pc, "force_steps"), 5);           // and sent its contact force back
  EXPECT_GT(jsonNumber(pc, "max_force_sent_n"), 0.05);
  EXPECT_LE(jsonNumber(pc, "max_force_sent_n"), 2.0 + 1e-9);  // --max-force default
  EXPECT_GT(displacementOf(pc, "ball"), 0.02);            // pushed out of its dimple (12.5 mm grid)
  EXPECT_GT(jsonNumber(hd, "client_force_ticks"), 5);     // hapticd applied it on the pen
  EXPECT_LE(jsonNumber(hd, "max_force_n"), 7.9 + 1e-9);
  if (jsonNumber(hd, "missed_ticks") == 0) {
    EXPECT_EQ(jsonNumber(hd, "faults"), 0);  // a VM stall may fault
  }
}
