#include "device/vrpn/system_messages.hpp"

#include <algorithm>
#include <string>

#include "device/vrpn/byte_io.hpp"
#include "device/vrpn/limits.hpp"

namespace thx::vrpn {

bool isValidName(std::string_view name) {
  return !name.empty() && name.size() <= kMaxNameLength && name.find('\0') == std::string_view::npos;
}

void encodeDescription(std::string_view name, std::vector<std::uint8_t>& out) {
  ByteWriter w(out);
  w.u32(std::uint32_t(name.size() + 1));
  w.chars(name);
  w.zeros(1);
}

Result<std::string_view> decodeDescription(std::span<const std::uint8_t> payload) {
  if (payload.size() > kMaxDescriptionPayload)
    return Error{ErrorCode::kBadDescription, "description body is " + std::to_string(payload.size()) +
                                                 " bytes, the limit is " + std::to_string(kMaxDescriptionPayload)};
  ByteReader r(payload);
  const std::uint32_t n = r.u32();
  if (!r.ok() || n != r.remaining())
    return Error{ErrorCode::kBadDescription, "description length word " + std::to_string(n) + " does not match its " +
                                                 std::to_string(payload.size()) + "-byte body"};
  const std::span<const std::uint8_t> raw = r.bytes(n);
  const auto end = std::find(raw.begin(), raw.end(), std::uint8_t{0});
  const std::string_view name(reinterpret_cast<const char*>(raw.data()), std::size_t(end - raw.begin()));
  if (name.empty()) return Error{ErrorCode::kBadDescription, "description with an empty name"};
  if (name.size() > kMaxNameLength)
    return Error{ErrorCode::kBadDescription,
                 "described name is longer than " + std::to_string(kMaxNameLength) + " bytes"};
  return name;
}

}  // namespace thx::vrpn
