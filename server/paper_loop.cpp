#include "server/paper_loop.hpp"

#include <algorithm>
#include <cmath>

#include "base/error.hpp"
#include "base/number_text.hpp"

namespace thx::srv {

int planeHoldTicks(double servo_hz, double plane_rate_hz) {
  if (!std::isfinite(plane_rate_hz) || plane_rate_hz <= 0.0 || plane_rate_hz > servo_hz) {
    throw thx::Error(thx::Error::Kind::Config, "paper loop: plane rate " + numberText(plane_rate_hz) +
                                                   " Hz: expected a rate > 0 and at most the servo rate " +
                                                   numberText(servo_hz) + " Hz");
  }
  return std::max(1, int(std::lround(servo_hz / plane_rate_hz)));
}

void applyPaperLoop(ServoRigConfig& wiring, double plane_rate_hz) {
  RendererConfig& rc = wiring.renderer;
  rc.crease_handling = false;
  rc.recovery_ticks = 0;
  rc.plane_hold_ticks = planeHoldTicks(1.0 / wiring.period_s, plane_rate_hz);
  wiring.passivity = false;
}

}  // namespace thx::srv
