#pragma once
// The whole servo pipeline around a simulated PHANToM, wired as hapticd wires it (server/hapticd.cpp):
// SimPhantom (lock-step) -> Servo { ProxyRenderer (or a CapsuleTool) -> PassivityController -> SafetyStage }
// -> SimPhantom.
// The stability map and its tests drive it one tick at a time and read the simulator's ground truth
// beside the tick record, so what they measure is what the pen really did, not what the encoders said.
//
// Not real-time code: construction allocates (server/servo_rig.hpp). Deterministic: the device runs
// on its own VirtualClock and nothing reads the wall clock except the servo's latency statistics,
// which the analysis ignores.
#include <memory>
#include <optional>

#include "device/hand_script.hpp"
#include "device/sim_phantom.hpp"
#include "server/capsule_tool.hpp"
#include "server/servo_rig.hpp"
#include "textures/textured_surface.hpp"

namespace thx::srv::stab {

struct RigOptions {
  double stiffness_n_per_m = 1000.0;
  double damping_ns_per_m = 0.0;  // the renderer's virtual damping B, along the spring
  bool crease_handling = true;
  int recovery_ticks = RendererConfig{}.recovery_ticks;
  bool passivity = true;
  int plane_hold_ticks = 1;  // RendererConfig::plane_hold_ticks (the paper's loop)
  bool sided_ridges = RendererConfig{}.sided_ridges;  // false: issue 3's blended ridges (--ridges blend)
  // A pen with extent: the servo renders this capsule tool (on the device's spec) instead of the
  // plane-proxy renderer. Its stiffness should be stiffness_n_per_m (the passivity observer's K).
  std::optional<CapsuleToolConfig> capsule;
};

class SimRig {
 public:
  // `surface` must outlive the rig. `sim` must be lock-step (the map must not depend on the host's speed).
  SimRig(const tex::TexturedSurface& surface, const dev::SimPhantomConfig& sim, dev::HandScript script,
         const RigOptions& options);

  // One servo tick (device read -> render -> passivity -> safety -> device write). The record is
  // valid until the next call; truth() then describes the same tick.
  const TickRecord& tick();

  const dev::SimTruth& truth() const { return device_->truth(); }
  dev::SimPhantom& device() { return *device_; }
  const ProxyRenderer& renderer() const { return rig_->renderer(); }
  const PassivityController& passivity() const { return rig_->passivity(); }
  const SafetyStage& safety() const { return rig_->safety(); }
  const Servo& servo() const { return rig_->servo(); }
  double periodS() const { return period_s_; }

 private:
  double period_s_;
  std::unique_ptr<dev::SimPhantom> device_;
  std::unique_ptr<CapsuleTool> tool_;  // RigOptions::capsule
  std::unique_ptr<ServoRig> rig_;
};

}  // namespace thx::srv::stab
