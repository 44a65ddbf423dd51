#pragma once
// What the tests' servo rigs (tests/server/servo_fixture.hpp, tests/vrpn/served_rig.hpp) build a
// srv::ServoRig on: a generated texture on a 0.1 m square, and the wiring of the servo's unit
// tests (server/servo_rig.hpp).
#include <memory>

#include "server/servo_rig.hpp"
#include "textures/generators.hpp"
#include "textures/textured_surface.hpp"

namespace thx::test {

// The texture `g` on a 0.1 m x 0.1 m plane; `relief` reads its alpha as depth.
struct GeneratedSurface {
  GeneratedSurface(const tex::GenerateRequest& g, bool relief)
      : map(std::make_unique<tex::TextureMap>(tex::generate(g))) {
    tex::PlaneMapping m;
    m.size_m = {0.1, 0.1};
    surface = std::make_unique<tex::TexturedSurface>(*map, m, tex::SampleOptions{}, relief);
  }
  std::unique_ptr<tex::TextureMap> map;
  std::unique_ptr<tex::TexturedSurface> surface;
};

// A 1 kHz servo at `stiffness_n_per_m`: passivity on without hapticd's quantisation play (a
// test device's positions are exact), one second of flight record, a 4096-record ring.
inline srv::ServoRigConfig unitTestWiring(double stiffness_n_per_m, bool crease = true) {
  srv::ServoRigConfig c;
  c.renderer.stiffness_n_per_m = stiffness_n_per_m;
  c.renderer.crease_handling = crease;
  c.period_s = 1e-3;
  c.quantisation_play = false;
  c.flight_record_ticks = 1000;
  c.ring_records = 4096;
  return c;
}

}  // namespace thx::test
