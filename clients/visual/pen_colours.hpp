#pragma once
// Each device's pen in its own colour (issue 30), so the pens of a multi-device scene can be told
// apart in a frame. Device 0 keeps the colours the one pen always had (a red ball, yellow while
// its proxy is held), so a one-device frame is unchanged; the table repeats after kPenPalette
// devices (a scene may have 16).
#include <Eigen/Core>
#include <array>

namespace thx::visual {

struct PenColours {
  Eigen::Vector3f ball;  // the ball at the tip; the small tip ball under a held proxy
  Eigen::Vector3f held;  // the ball on the proxy while it is held (the tip below the surface)
};

inline constexpr int kPenPalette = 4;

// Device `device`'s colours (its index in hello_t.device_names); a negative index as device 0.
inline PenColours penColours(int device) {
  // Hues far apart from each other and from the plane's grey-beige; each held colour a lighter
  // neighbour of its ball's, as device 0's yellow is of its red.
  static const std::array<PenColours, kPenPalette> table{{
      {{0.85f, 0.15f, 0.1f}, {0.95f, 0.85f, 0.3f}},   // red, held yellow
      {{0.15f, 0.3f, 0.9f}, {0.35f, 0.85f, 0.95f}},   // blue, held cyan
      {{0.15f, 0.65f, 0.15f}, {0.6f, 0.95f, 0.35f}},  // green, held lime
      {{0.75f, 0.15f, 0.75f}, {0.95f, 0.6f, 0.9f}},   // magenta, held pink
  }};
  return table[std::size_t(device < 0 ? 0 : device % kPenPalette)];
}

}  // namespace thx::visual
