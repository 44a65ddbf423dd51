#include "device/vrpn/frame.hpp"

namespace thx::vrpn {

bool appendFrame(std::vector<std::uint8_t>& out, Header header, std::span<const std::uint8_t> payload) {
  if (payload.size() > kMaxPayloadLength) return false;
  header.payload_length = std::uint32_t(payload.size());
  ByteWriter w(out);
  writeHeader(w, header);
  w.bytes(payload);
  w.zeros(paddedLength(payload.size()) - payload.size());
  return true;
}

}  // namespace thx::vrpn
