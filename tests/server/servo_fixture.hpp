#pragma once
// A servo wired as hapticd wires it (server/servo_rig.hpp) around a V-valley relief map, driven by
// a scripted FakeDevice. The passivity controller runs without hapticd's quantisation dead band
// (the fake device's positions are exact).
#include <memory>

#include "server/servo_rig.hpp"
#include "tests/server/fake_device.hpp"
#include "textures/generators.hpp"

namespace thx::test {

// What the servo rig is built on; a base so that it exists before the rig.
struct ServoRigInputs {
  explicit ServoRigInputs(FakeDevice::Script script) : device(std::move(script)) {
    tex::GenerateRequest g;
    g.kind = "vvalley";
    g.size = 256;
    g.params = {{"angle_deg", 60.0}, {"period", 0.004}, {"extent", 0.1}};
    map = std::make_unique<tex::TextureMap>(tex::generate(g));
    tex::PlaneMapping m;
    m.size_m = {0.1, 0.1};
    surface = std::make_unique<tex::TexturedSurface>(*map, m, tex::SampleOptions{}, true);
  }
  static srv::ServoRigConfig wiring(bool crease) {
    srv::ServoRigConfig c;
    c.renderer.stiffness_n_per_m = 1000.0;
    c.renderer.crease_handling = crease;
    c.period_s = 1e-3;
    c.quantisation_deadband = false;
    c.flight_record_ticks = 1000;
    c.ring_records = 4096;
    return c;
  }

  FakeDevice device;
  std::unique_ptr<tex::TextureMap> map;
  std::unique_ptr<tex::TexturedSurface> surface;
};

struct ServoRig : ServoRigInputs, srv::ServoRig {
  explicit ServoRig(FakeDevice::Script script, bool crease = true)
      : ServoRigInputs(std::move(script)), srv::ServoRig(device, *surface, wiring(crease)) {}

  // Runs n ticks, draining the ring as a publisher would.
  void run(int n) {
    for (int k = 0; k < n; ++k) tickAndDrain();
  }
};

// Valley floors of the rig's map (extent 0.1 m, period 4 mm): x = k * 4 mm; depth 3.46 mm.
inline constexpr double kRigFloorX = 0.0;
inline constexpr double kRigValleyDepth = 0.0034641016151377548;

}  // namespace thx::test
