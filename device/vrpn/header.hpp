#pragma once
// The 24-byte message header (docs/vrpn.md §4), all words big-endian:
//   0 length   = 24 + UNPADDED payload length (the receiver infers the padding)
//   4 tv_sec, 8 tv_usec   sender's timestamp
//  12 sender   sender id, or data for system messages (e.g. a UDP port)
//  16 type     >= 0 user type id, < 0 system type
//  20 sequence per-channel counter; information only, receivers ignore it
// The payload follows, padded with unspecified bytes to a multiple of 8.
//
// Contract: decodeHeader accepts lengths in [24, kMaxFrameLength] and rejects anything else, so
// no caller ever waits for or buffers more than kMaxFrameLength bytes for one message.
#include <cstddef>
#include <cstdint>
#include <span>

#include "device/vrpn/byte_io.hpp"
#include "device/vrpn/error.hpp"
#include "device/vrpn/limits.hpp"

namespace thx::vrpn {

// gettimeofday-style wall-clock stamp. Unsigned on the wire so it survives 2038; not validated
// (it is the sender's clock, information only).
struct TimeValue {
  std::uint32_t sec = 0;
  std::uint32_t usec = 0;
  bool operator==(const TimeValue&) const = default;
};

TimeValue wallClockNow();

struct Header {
  std::uint32_t payload_length = 0;  // unpadded; length word - 24
  TimeValue time;
  std::int32_t sender = 0;
  std::int32_t type = 0;
  std::uint32_t sequence = 0;
  bool operator==(const Header&) const = default;
};

// (n + 7) & ~7: the payload's size on the wire.
constexpr std::size_t paddedLength(std::size_t payload_length) { return (payload_length + 7) & ~std::size_t{7}; }

// Bytes a whole message occupies on the wire: header + padded payload.
constexpr std::size_t frameSize(std::size_t payload_length) { return kHeaderSize + paddedLength(payload_length); }

// Writes the 24 header bytes; the length word is 24 + h.payload_length.
void writeHeader(ByteWriter& w, const Header& h);

// `bytes` must hold at least kHeaderSize bytes; only the first 24 are read.
Result<Header> decodeHeader(std::span<const std::uint8_t> bytes);

}  // namespace thx::vrpn
