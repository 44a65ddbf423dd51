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
    : period_s_(double(sim.servo_period_ns) * 1e-9) {
  if (!sim.lockstep) throw std::logic_error("SimRig: the simulated device must run lock-step");
  device_ = std::make_unique<dev::SimPhantom>(sim, std::move(script));
  ServoRigConfig c;
  c.renderer.stiffness_n_per_m = options.stiffness_n_per_m;
  c.renderer.damping_ns_per_m = options.damping_ns_per_m;
  c.renderer.crease_handling = options.crease_handling;
  c.renderer.recovery_ticks = options.recovery_ticks;
  c.renderer.plane_hold_ticks = options.plane_hold_ticks;
  c.renderer.sided_ridges = options.sided_ridges;
  c.period_s = period_s_;
  c.passivity = options.passivity;
  c.quantisation_play = true;  // as hapticd
  c.flight_record_ticks = kFlightRecordTicks;
  c.ring_records = kRingRecords;
  if (options.capsule) tool_ = std::make_unique<CapsuleTool>(surface, sim.spec, *options.capsule);
  rig_ = std::make_unique<ServoRig>(*device_, surface, c, nullptr, tool_.get());
  device_->open();
}

const TickRecord& SimRig::tick() { return rig_->tickAndDrain(); }

}  // namespace thx::srv::stab
