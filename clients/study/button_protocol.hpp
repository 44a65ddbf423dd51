#pragma once
// The device button as the participant's only input during a trial (docs/study.md §5.2):
//  - a short press of button 1 (bit 0; released within long_press_s) = NEXT: show the next
//    candidate look (Study 1) or switch to the next surface (Study 2), on release;
//  - holding button 1 for long_press_s = CONFIRM: this look is my answer (Study 1), rate this
//    surface now (Study 2), given the moment the hold reaches long_press_s; the release after it
//    gives nothing;
//  - pressing button 2 (bit 1), where the stylus has one, = CONFIRM at once;
//  - presses shorter than min_press_s are contact bounce and give nothing.
// Fed one device_state_t's buttons per tick (real mode) or the simulated hand's (--simulate).
#include <cstdint>

namespace thx::study {

enum class ButtonEvent { None, Next, Confirm };

struct ButtonProtocolConfig {
  double long_press_s = 0.8;
  double min_press_s = 0.02;
};

class ButtonProtocol {
 public:
  explicit ButtonProtocol(ButtonProtocolConfig config = {}) : config_(config) {}
  // t_s must not decrease between calls.
  ButtonEvent update(double t_s, std::uint32_t buttons);
  const ButtonProtocolConfig& config() const { return config_; }

 private:
  ButtonProtocolConfig config_;
  bool down1_ = false, down2_ = false;
  bool confirmed_ = false;  // the current hold of button 1 already gave CONFIRM
  double pressed_at_s_ = 0.0;
};

}  // namespace thx::study
