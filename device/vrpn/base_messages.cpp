#include "device/vrpn/base_messages.hpp"

#include <algorithm>

#include "device/vrpn/limits.hpp"
#include "device/vrpn/payload_size.hpp"

namespace thx::vrpn {

Result<Ping> Ping::decode(std::span<const std::uint8_t> payload) {
  if (auto e = checkSize(kTypeName, payload, 0)) return *e;
  return Ping{};
}

Result<Pong> Pong::decode(std::span<const std::uint8_t> payload) {
  if (auto e = checkSize(kTypeName, payload, 0)) return *e;
  return Pong{};
}

void TextMessage::encode(ByteWriter& w) const {
  w.u32(severity);
  w.u32(level);
  const std::string_view t = std::string_view(text).substr(0, std::min(text.find('\0'), kTextBufferSize - 1));
  w.chars(t);
  w.zeros(kTextBufferSize - t.size());
}

Result<TextMessage> TextMessage::decode(std::span<const std::uint8_t> payload) {
  if (payload.size() < 8 || payload.size() > 8 + kTextBufferSize)
    return sizeError(kTypeName, payload.size(), "8.." + std::to_string(8 + kTextBufferSize));
  ByteReader r(payload);
  TextMessage m;
  m.severity = r.u32();
  m.level = r.u32();
  const std::span<const std::uint8_t> rest = r.bytes(r.remaining());
  const auto end = std::find(rest.begin(), rest.end(), std::uint8_t{0});
  m.text.assign(rest.begin(), end);
  return m;
}

}  // namespace thx::vrpn
