#include "device/vrpn/button_messages.hpp"

#include <algorithm>
#include <string>

#include "device/vrpn/limits.hpp"
#include "device/vrpn/payload_size.hpp"

namespace thx::vrpn {

void ButtonChange::encode(ByteWriter& w) const {
  w.i32(button);
  w.i32(state);
}

Result<ButtonChange> ButtonChange::decode(std::span<const std::uint8_t> payload) {
  if (auto e = checkSize(kTypeName, payload, kSize)) return *e;
  ByteReader r(payload);
  ButtonChange m;
  m.button = r.i32();
  m.state = r.i32();
  return m;
}

void ButtonStates::encode(ByteWriter& w) const {
  const std::size_t n = std::min(states.size(), kMaxButtons);
  w.i32(std::int32_t(n));
  for (std::size_t i = 0; i < n; ++i) w.i32(states[i]);
}

Result<ButtonStates> ButtonStates::decode(std::span<const std::uint8_t> payload) {
  if (payload.size() < 4)
    return sizeError(kTypeName, payload.size(), "at least 4");
  ByteReader r(payload);
  const std::int32_t n = r.i32();
  if (n < 0 || std::size_t(n) > kMaxButtons)
    return Error{ErrorCode::kBadValue,
                 std::string(kTypeName) + " count " + std::to_string(n) + " outside 0.." + std::to_string(kMaxButtons)};
  // Size checked before the count is trusted for an allocation.
  if (auto e = checkSize(kTypeName, payload, 4 + 4 * std::size_t(n))) return *e;
  ButtonStates m;
  m.states.resize(std::size_t(n));
  for (std::int32_t& s : m.states) s = r.i32();
  return m;
}

}  // namespace thx::vrpn
