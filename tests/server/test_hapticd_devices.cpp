// hapticd with a scene of several devices (issue 30), as a user runs it: the shipped two-pen
// scene in lock-step, each pen's own statistics and its equality with the same pen alone, the
// options that cannot apply to several devices, and both pens served to a VRPN client under
// their scene names.
#include <gtest/gtest.h>

#include <atomic>
#include <fstream>
#include <thread>

#include "tests/support/hapticd_harness.hpp"
#include "tests/support/vrpn_reports.hpp"

namespace test_hapticd_devices {

using namespace thx::test;
using HapticdDevices = thx::test::HapticdProcessTest;

namespace {

// The entry of the --stats-json "devices" list named `name` (its text up to the closing brace).
std::string deviceEntry(const std::string& json, const std::string& name) {
  const std::size_t list = json.find("\"devices\": [");
  if (list == std::string::npos) return "";
  const std::size_t at = json.find("{\"name\": \"" + name + "\"", list);
  if (at == std::string::npos) return "";
  return json.substr(at, json.find('}', at) - at + 1);
}

// scenes/two_pens.yaml with only the device named `name`, as a one-device scene.
std::string oneOfTheTwoPens(const std::string& name) {
  std::ifstream in(std::string(THX_SOURCE_DIR) + "/scenes/two_pens.yaml");
  std::string text, line, device;
  bool in_devices = false, in_this = false;
  while (std::getline(in, line)) {
    if (line == "devices:") {
      in_devices = true;
      continue;
    }
    if (in_devices && line.rfind("  - name: ", 0) == 0) {
      in_this = line == "  - name: " + name;
      continue;
    }
    if (in_devices && !line.empty() && line[0] != ' ') in_devices = false;
    if (!in_devices) {
      text += line + "\n";
    } else if (in_this && line.size() > 2) {
      device += line.substr(2) + "\n";  // one level up: a `device:` section's fields
    }
  }
  return text + "device:\n" + device;
}

}  // namespace

TEST_F(HapticdDevices, TwoPensRunInLockstepEachAsItWouldAlone) {
  // One duration for both runs: the same stop tick, so the same ticks to compare.
  ProcRun r = run("--scene scenes/two_pens.yaml --lockstep --no-lcm --quiet --duration 5 --stats-json '" + path("two.json") +
                  "' --flight-dir '" + path("") + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err, "") << "the shipped scene starts without a warning";
  const std::string two = slurp(path("two.json"));
  EXPECT_NE(r.out.find("device left"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("device right"), std::string::npos) << r.out;
  EXPECT_EQ(jsonNumber(two, "missed_ticks"), 0);
  for (const char* name : {"left", "right"}) {
    SCOPED_TRACE(name);
    const std::string pen = deviceEntry(two, name);
    ASSERT_FALSE(pen.empty()) << two;
    EXPECT_GT(jsonNumber(pen, "contact_ticks"), 1000) << pen;
    EXPECT_EQ(jsonNumber(pen, "faults"), 0);
    EXPECT_EQ(jsonNumber(pen, "full_force_percent"), 100.0);
    EXPECT_LE(jsonNumber(pen, "max_force_n"), 7.9);

    // The same pen alone in a one-device scene: one servo clock changes nothing of its force.
    std::ofstream(path(std::string(name) + ".yaml")) << oneOfTheTwoPens(name);
    r = run("--scene '" + path(std::string(name) + ".yaml") + "' --lockstep --no-lcm --quiet --duration 5 --stats-json '" +
            path("alone.json") + "' --flight-dir '" + path("") + "'");
    ASSERT_EQ(r.status, 0) << r.err;
    const std::string alone = slurp(path("alone.json"));
    EXPECT_EQ(jsonNumber(alone, "ticks"), jsonNumber(two, "ticks"));
    EXPECT_EQ(jsonNumber(alone, "contact_ticks"), jsonNumber(pen, "contact_ticks"));
    EXPECT_EQ(jsonNumber(alone, "max_force_n"), jsonNumber(pen, "max_force_n"));
  }
}

TEST_F(HapticdDevices, OptionsThatNameOneDeviceAreRefusedWithTheReason) {
  struct Case {
    const char* args;
    const char* expect;
  };
  for (const Case& c : {Case{"--device sim", "--device replaces a scene's one device"},
                        Case{"--record x.lcmlog", "--record writes one device's session so far"},
                        Case{"--vrpn-listen 3883 --vrpn-name Pen", "--vrpn-name names one device"}}) {
    SCOPED_TRACE(c.args);
    const ProcRun r = run(std::string("--scene scenes/two_pens.yaml --lockstep --no-lcm ") + c.args);
    EXPECT_EQ(r.status, 1) << r.err;
    EXPECT_NE(r.err.find("two_pens.yaml: the scene lists 2 devices"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(c.expect), std::string::npos) << r.err;
  }
  // --lockstep with a VRPN device among several: named.
  std::ofstream(path("mixed.yaml")) << "version: 1\nname: mixed\nsurface:\n  size: [0.2, 0.2]\n"
                                       "  texture: {generator: bricks, size: 64}\n"
                                       "devices:\n  - {name: pen}\n  - {name: far, type: vrpn, address: "
                                       "Phantom0@127.0.0.1:1}\n";
  const ProcRun r = run("--scene '" + path("mixed.yaml") + "' --lockstep --no-lcm");
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_NE(r.err.find("--lockstep needs simulated or replayed devices; device far is VRPN"), std::string::npos)
      << r.err;
}

// A VRPN client naming both pens on one connection gets the reports of each under its name, and
// each follows its own pen (the left pen strokes along x, the right one first presses).
TEST_F(HapticdDevices, BothPensAreServedToAVrpnClientUnderTheirNames) {
  const std::uint16_t port = sparePort();
  ProcRun server;
  std::atomic<bool> server_done{false};
  std::thread proc([&] {
    server = run("--scene scenes/two_pens.yaml --duration 3 --no-lcm --no-mlock --vrpn-listen " + std::to_string(port));
    server_done = true;
  });
  const VrpnReports got = readVrpnReports(port, {"left", "right"}, server_done);
  proc.join();
  EXPECT_EQ(server.status, 0) << server.err;
  EXPECT_NE(server.err.find("serving left,right to VRPN apps"), std::string::npos) << server.err;
  // How many reports arrive depends on the scheduler; that both pens' arrive, each moving, does not.
  EXPECT_TRUE(got.connected);
  EXPECT_EQ(got.unnamed_senders, 0);
  for (const char* n : {"left", "right"}) {
    SCOPED_TRACE(n);
    const SenderReports& pen = got.by_name.at(n);
    EXPECT_GT(pen.reports, 0);
    EXPECT_EQ(pen.undecodable, 0);
    EXPECT_GT(pen.x_max - pen.x_min, 0.0);
  }
}

}  // namespace test_hapticd_devices
