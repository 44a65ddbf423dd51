#pragma once
// Everything a servo needs, wired as hapticd wires it, around a V-valley relief map.
#include <memory>

#include "server/servo.hpp"
#include "tests/server/fake_device.hpp"
#include "textures/generators.hpp"

namespace thx::test {

struct ServoRig {
  explicit ServoRig(FakeDevice::Script script, bool crease = true) : device(std::move(script)) {
    tex::GenerateRequest g;
    g.kind = "vvalley";
    g.size = 256;
    g.params = {{"angle_deg", 60.0}, {"period", 0.004}, {"extent", 0.1}};
    map = std::make_unique<tex::TextureMap>(tex::generate(g));
    tex::PlaneMapping m;
    m.size_m = {0.1, 0.1};
    surface = std::make_unique<tex::TexturedSurface>(*map, m, tex::SampleOptions{}, true);
    srv::RendererConfig rc;
    rc.stiffness_n_per_m = 1000.0;
    rc.crease_handling = crease;
    renderer = std::make_unique<srv::ProxyRenderer>(*surface, rc);
    passivity = std::make_unique<srv::PassivityController>(srv::PassivityConfig::fromSpec(device.spec(), 1e-3, 1000.0));
    safety = std::make_unique<srv::SafetyStage>(srv::SafetyConfig::fromSpec(device.spec(), 1e-3));
    servo = std::make_unique<srv::Servo>(device, *renderer, *passivity, *safety, recorder, ring, srv::ServoConfig{});
  }

  // Runs n ticks, draining the ring as a publisher would.
  void run(int n) {
    srv::TickRecord r;
    for (int k = 0; k < n; ++k) {
      servo->tick();
      while (ring.pop(r)) {
      }
    }
  }

  FakeDevice device;
  std::unique_ptr<tex::TextureMap> map;
  std::unique_ptr<tex::TexturedSurface> surface;
  std::unique_ptr<srv::ProxyRenderer> renderer;
  std::unique_ptr<srv::PassivityController> passivity;
  std::unique_ptr<srv::SafetyStage> safety;
  srv::FlightRecorder recorder{1000};
  rt::SpscRing<srv::TickRecord> ring{4096};
  std::unique_ptr<srv::Servo> servo;
};

// Valley floors of the rig's map (extent 0.1 m, period 4 mm): x = k * 4 mm; depth 3.46 mm.
inline constexpr double kRigFloorX = 0.0;
inline constexpr double kRigValleyDepth = 0.0034641016151377548;

}  // namespace thx::test
