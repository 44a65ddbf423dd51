#include "clients/study/button_protocol.hpp"

namespace thx::study {

ButtonEvent ButtonProtocol::update(double t_s, std::uint32_t buttons) {
  const bool b1 = (buttons & 1u) != 0, b2 = (buttons & 2u) != 0;
  ButtonEvent e = ButtonEvent::None;
  if (b2 && !down2_) e = ButtonEvent::Confirm;
  down2_ = b2;
  if (b1 && !down1_) {
    pressed_at_s_ = t_s;
    confirmed_ = false;
  } else if (b1 && !confirmed_ && t_s - pressed_at_s_ >= config_.long_press_s) {
    confirmed_ = true;
    e = ButtonEvent::Confirm;
  } else if (!b1 && down1_ && !confirmed_ && t_s - pressed_at_s_ >= config_.min_press_s) {
    if (e == ButtonEvent::None) e = ButtonEvent::Next;
  }
  down1_ = b1;
  return e;
}

}  // namespace thx::study
