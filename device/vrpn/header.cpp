#include "device/vrpn/header.hpp"

#include <chrono>
#include <string>

namespace thx::vrpn {

TimeValue wallClockNow() {
  const auto us =
      std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::system_clock::now().time_since_epoch())
          .count();
  return TimeValue{std::uint32_t(us / 1'000'000), std::uint32_t(us % 1'000'000)};
}

void writeHeader(ByteWriter& w, const Header& h) {
  w.u32(std::uint32_t(kHeaderSize) + h.payload_length);
  w.u32(h.time.sec);
  w.u32(h.time.usec);
  w.i32(h.sender);
  w.i32(h.type);
  w.u32(h.sequence);
}

Result<Header> decodeHeader(std::span<const std::uint8_t> bytes) {
  if (bytes.size() < kHeaderSize)
    return Error{ErrorCode::kTruncated, "header needs 24 bytes, have " + std::to_string(bytes.size())};
  ByteReader r(bytes.first(kHeaderSize));
  const std::uint32_t length = r.u32();
  if (length < kHeaderSize)
    return Error{ErrorCode::kLengthTooSmall,
                 "message length " + std::to_string(length) + " is below the 24-byte header"};
  if (length > kMaxFrameLength)
    return Error{ErrorCode::kLengthTooLarge, "message length " + std::to_string(length) + " exceeds the limit of " +
                                                 std::to_string(kMaxFrameLength)};
  Header h;
  h.payload_length = length - std::uint32_t(kHeaderSize);
  h.time.sec = r.u32();
  h.time.usec = r.u32();
  h.sender = r.i32();
  h.type = r.i32();
  h.sequence = r.u32();
  return h;
}

}  // namespace thx::vrpn
