#include "server/tools/stability_map_rig.hpp"

#include <stdexcept>
#include <utility>

namespace thx::srv::stab {

namespace {
// hapticd keeps one second of ticks; a fault in a map cell is analysed from the truth instead,
// so a short record is enough and keeps thousands of cells cheap.
constexpr std::size_t kFlightRecordTicks = 64;
constexpr std::size_t kRingRecords = 8;  // drained every tick, as hapticd's publisher would
}  // namespace

SimRig::SimRig(const tex::TexturedSurface& surface, const dev::SimPhantomConfig& sim, dev::HandScript script,
               const RigOptions& options)
    : period_s_(double(sim.servo_period_ns) * 1e-9), recorder_(kFlightRecordTicks), ring_(kRingRecords) {
  if (!sim.lockstep) throw std::invalid_argument("SimRig: the simulated device must run lock-step");
  device_ = std::make_unique<dev::SimPhantom>(sim, std::move(script));
  RendererConfig rc;
  rc.stiffness_n_per_m = options.stiffness_n_per_m;
  rc.damping_ns_per_m = options.damping_ns_per_m;
  rc.crease_handling = options.crease_handling;
  rc.recovery_ticks = options.recovery_ticks;
  renderer_ = std::make_unique<ProxyRenderer>(surface, rc);
  passivity_ = std::make_unique<PassivityController>(
      servoPassivityConfig(device_->spec(), period_s_, options.stiffness_n_per_m, options.passivity));
  safety_ = std::make_unique<SafetyStage>(SafetyConfig::fromSpec(device_->spec(), period_s_));
  servo_ = std::make_unique<Servo>(*device_, *renderer_, *passivity_, *safety_, recorder_, ring_, ServoConfig{});
  device_->open();
}

const TickRecord& SimRig::tick() {
  const TickRecord& r = servo_->tick();
  TickRecord drained;
  while (ring_.pop(drained)) {
  }
  return r;
}

}  // namespace thx::srv::stab
