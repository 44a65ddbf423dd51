#pragma once
// Fixed limits of the VRPN wire protocol layer (docs/vrpn.md §4, §5, §8).
//
// Every buffer the decoder allocates from a length the peer chose is bounded by one of these, so
// a hostile peer can make us reject its input but never make us allocate more than
// kMaxFrameLength per connection for framing (plus what the caller feeds between polls), or more
// than kMaxNames short names per table.
#include <cstddef>
#include <cstdint>

namespace thx::vrpn {

// Each message starts with six big-endian 32-bit words.
inline constexpr std::size_t kHeaderSize = 24;

// The stock receiver reads a TCP message into a 64000-byte buffer, so nothing longer can be valid
// on the wire. Header lengths above this are rejected before any payload is buffered.
inline constexpr std::size_t kMaxFrameLength = 64000;
inline constexpr std::size_t kMaxPayloadLength = kMaxFrameLength - kHeaderSize;

// Stock peers register at most 2000 senders and 2000 types; ids outside [0, 2000) are invalid.
inline constexpr std::int32_t kMaxNames = 2000;

// A description payload over 100 bytes drops the link at a stock receiver: 4-byte length word +
// name + NUL, so a name has at most 95 characters.
inline constexpr std::size_t kMaxDescriptionPayload = 100;
inline constexpr std::size_t kMaxNameLength = kMaxDescriptionPayload - 4 - 1;

// vrpn_Button States carries at most 256 buttons.
inline constexpr std::size_t kMaxButtons = 256;

// vrpn_Base text_message: two words + a 1024-byte NUL-terminated buffer, always sent whole.
inline constexpr std::size_t kTextBufferSize = 1024;

// What an Endpoint queues for a peer that does not read before it gives up on that peer.
inline constexpr std::size_t kDefaultMaxPendingOutput = std::size_t{1} << 20;

}  // namespace thx::vrpn
