#pragma once
// A servo wired as hapticd wires it (server/servo_rig.hpp) around a V-valley relief map, driven by
// a scripted FakeDevice. The passivity controller runs without hapticd's quantisation play
// (the fake device's positions are exact).
#include <memory>

#include "server/servo_rig.hpp"
#include "tests/server/fake_device.hpp"
#include "tests/support/servo_inputs.hpp"

namespace thx::test {

// What the servo rig is built on; a base so that it exists before the rig.
struct ServoRigInputs {
  explicit ServoRigInputs(FakeDevice::Script script)
      : device(std::move(script)), texture(vvalley(), /*relief=*/true) {}
  static tex::GenerateRequest vvalley() {
    tex::GenerateRequest g;
    g.kind = "vvalley";
    g.size = 256;
    g.params = {{"angle_deg", 60.0}, {"period", 0.004}, {"extent", 0.1}};
    return g;
  }

  FakeDevice device;
  GeneratedSurface texture;
};

struct ServoRig : ServoRigInputs, srv::ServoRig {
  explicit ServoRig(FakeDevice::Script script, bool crease = true,
                    srv::MissedTickMode missed = srv::MissedTickMode::RideThrough)
      : ServoRigInputs(std::move(script)), srv::ServoRig(device, *texture.surface, wiring(crease, missed)) {}
  static srv::ServoRigConfig wiring(bool crease, srv::MissedTickMode missed) {
    srv::ServoRigConfig c = unitTestWiring(1000.0, crease);
    c.missed_mode = missed;
    return c;
  }

  // Runs n ticks, draining the ring as a publisher would.
  void run(int n) {
    for (int k = 0; k < n; ++k) tickAndDrain();
  }
};

// Valley floors of the rig's map (extent 0.1 m, period 4 mm): x = k * 4 mm; depth 3.46 mm.
inline constexpr double kRigFloorX = 0.0;
inline constexpr double kRigValleyDepth = 0.0034641016151377548;

}  // namespace thx::test
