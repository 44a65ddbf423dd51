#include "server/servo_rig.hpp"

namespace thx::srv {

namespace {
PassivityConfig passivityFor(const dev::DeviceSpec& spec, const ServoRigConfig& c) {
  PassivityConfig p = servoPassivityConfig(spec, c.period_s, c.renderer.stiffness_n_per_m, c.passivity);
  if (!c.quantisation_play) p.quantisation_play_m = 0.0;  // PassivityConfig::fromSpec()'s
  return p;
}
ServoConfig servoConfigFor(const dev::DeviceSpec& spec, const ServoRigConfig& c) {
  ServoConfig s = c.servo;
  s.missed = MissedTickPolicyConfig::fromSpec(spec, c.renderer.stiffness_n_per_m, c.missed_mode, c.period_s);
  return s;
}
}  // namespace

ServoRig::ServoRig(dev::HapticDevice& device, const tex::TexturedSurface& surface, const ServoRigConfig& config,
                   TexturedMeshRenderer* mesh, CapsuleTool* tool)
    : config_(config),
      renderer_(surface, config.renderer),
      passivity_(passivityFor(device.spec(), config)),
      safety_(SafetyConfig::fromSpec(device.spec(), config.period_s)),
      recorder_(config.flight_record_ticks),
      ring_(config.ring_records),
      servo_(device, renderer_, passivity_, safety_, recorder_, ring_, servoConfigFor(device.spec(), config),
             mesh, tool) {}

const TickRecord& ServoRig::tickAndDrain() {
  const TickRecord& r = servo_.tick();
  drain();
  return r;
}

void ServoRig::drain() {
  TickRecord r;
  while (ring_.pop(r)) {
  }
}

void ServoRig::reset() {
  servo_.resetRenderer();
  passivity_.reset();
  safety_.reset();
  drain();
}

}  // namespace thx::srv
