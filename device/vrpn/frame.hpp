#pragma once
// One message on the wire: header + payload + zero padding to a multiple of 8 (docs/vrpn.md §4).
//
// Contract: appendFrame writes padding as zeros (receivers ignore its contents; stock senders
// leave garbage there) and takes the length from the payload, ignoring header.payload_length.
// It refuses (returns false, appends nothing) payloads over kMaxPayloadLength, which a stock
// receiver could not take.
#include <cstdint>
#include <span>
#include <vector>

#include "device/vrpn/header.hpp"

namespace thx::vrpn {

// A decoded message; `payload` (unpadded) points into the decoder's buffer, see FrameDecoder.
struct Frame {
  Header header;
  std::span<const std::uint8_t> payload;
};

bool appendFrame(std::vector<std::uint8_t>& out, Header header, std::span<const std::uint8_t> payload);

}  // namespace thx::vrpn
