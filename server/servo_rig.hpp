#pragma once
// The servo wired: the one place that builds a Servo and the parts it runs on (renderer,
// passivity controller, safety stage, flight recorder, tick ring). hapticd, the benchmarks, the
// stability map and the tests all build their servo here, so what they run is what hapticd runs.
//
// Construction allocates (renderer scratch, flight recorder, ring); tick() and tickAndDrain() do
// not (servo.hpp's contract; tests/server/test_servo_no_alloc.cpp). Not copyable or movable: the
// Servo holds references to its neighbours. The device and the surface belong to the caller and
// must outlive the rig, and so must a mesh scene's renderer (mesh_scene.hpp) given to it.
#include <cstddef>

#include "device/haptic_device.hpp"
#include "rt/spsc_ring.hpp"
#include "server/flight_recorder.hpp"
#include "server/passivity.hpp"
#include "server/proxy_renderer.hpp"
#include "server/safety.hpp"
#include "server/servo.hpp"
#include "server/tick_record.hpp"
#include "textures/textured_surface.hpp"

namespace thx::srv {

struct ServoRigConfig {
  RendererConfig renderer;      // its stiffness is also the passivity observer's stored-energy K
  double period_s = 1e-3;       // the servo period (passivity and safety are tuned to it)
  bool passivity = true;        // the controller acts (the observer always runs)
  // hapticd's quantisation play of one encoder count (quantisationPlay()); off, the controller
  // is PassivityConfig::fromSpec() as it stands (the servo's unit tests).
  bool quantisation_play = true;
  std::size_t flight_record_ticks = 1000;  // hapticd: one second of ticks
  std::size_t ring_records = 1024;         // hapticd: 1 s of ticks, drained every 0.5 ms
  // What a gap in the servo's ticks does (server/missed_tick_policy.hpp); the rig sets
  // servo.missed from the device and the stiffness (MissedTickPolicyConfig::fromSpec) in this mode.
  MissedTickMode missed_mode = MissedTickMode::RideThrough;
  ServoConfig servo;
};

// hapticd's wiring for a scene lives beside the scene translation: srv::servoRigConfigFor()
// (server/scene_device.hpp).

class ServoRig {
 public:
  // `mesh`: a mesh scene's renderer, which the servo renders instead of the plane's (servo.hpp);
  // `surface` then only seeds the plane's renderer, unused until a switch to a plane scene.
  // `tool`: a capsule tool (device.tool: capsule; it must outlive the rig), rendered instead of both.
  ServoRig(dev::HapticDevice& device, const tex::TexturedSurface& surface, const ServoRigConfig& config,
           TexturedMeshRenderer* mesh = nullptr, CapsuleTool* tool = nullptr);
  ServoRig(const ServoRig&) = delete;
  ServoRig& operator=(const ServoRig&) = delete;

  // One servo tick (servo.hpp). Real-time safe.
  const TickRecord& tick() { return servo_.tick(); }
  // One tick, then the ring emptied as hapticd's publisher would (for rigs with no publisher).
  const TickRecord& tickAndDrain();
  // Empties the tick ring. Real-time safe.
  void drain();
  // The renderer in use, passivity and safety back to their state after construction, the ring emptied
  // (the device and the servo's counters are not touched).
  void reset();

  Servo& servo() { return servo_; }
  const Servo& servo() const { return servo_; }
  ProxyRenderer& renderer() { return renderer_; }
  const ProxyRenderer& renderer() const { return renderer_; }
  PassivityController& passivity() { return passivity_; }
  const PassivityController& passivity() const { return passivity_; }
  SafetyStage& safety() { return safety_; }
  const SafetyStage& safety() const { return safety_; }
  FlightRecorder& recorder() { return recorder_; }
  rt::SpscRing<TickRecord>& ring() { return ring_; }
  const ServoRigConfig& config() const { return config_; }

 private:
  ServoRigConfig config_;
  ProxyRenderer renderer_;
  PassivityController passivity_;
  SafetyStage safety_;
  FlightRecorder recorder_;
  rt::SpscRing<TickRecord> ring_;
  Servo servo_;
};

}  // namespace thx::srv
