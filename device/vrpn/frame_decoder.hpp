#pragma once
// Streaming message splitter: bytes in, whole messages out, in any chunking (one byte at a time
// works). No cookie handling here; see Endpoint.
//
// Contract:
//  - feed() appends; next() returns the next whole message, NeedMore, or an Error.
//  - A header is validated as soon as its 24 bytes are in: a bad length is reported before any of
//    its payload arrives, and the decoder never waits for more than kMaxFrameLength bytes for one
//    message. It never allocates from a length field; its buffer holds what the caller fed and has
//    not yet consumed, so the caller bounds memory by draining next() after each feed().
//  - Errors are sticky: after the first, feed() is ignored and next() repeats the error.
//  - A returned Frame's payload stays valid until the next feed() call.
//  - Padding contents are ignored.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <variant>
#include <vector>

#include "device/vrpn/error.hpp"
#include "device/vrpn/frame.hpp"

namespace thx::vrpn {

struct NeedMore {};

using DecodeStep = std::variant<NeedMore, Frame, Error>;

class FrameDecoder {
 public:
  void feed(std::span<const std::uint8_t> bytes);
  DecodeStep next();

  // Bytes fed but not yet returned in a message (a partial message at end of input).
  std::size_t buffered() const { return buffer_.size() - pos_; }
  // At end of input: kTruncated if a partial message is left, else nothing.
  std::optional<Error> finish() const;
  const std::optional<Error>& error() const { return error_; }

 private:
  std::vector<std::uint8_t> buffer_;
  std::size_t pos_ = 0;  // start of the first unconsumed byte
  std::optional<Error> error_;
};

}  // namespace thx::vrpn
