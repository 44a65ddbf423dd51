#pragma once
// Messages common to every device (docs/vrpn.md §6), sent with the device's name as sender.
//
// Each message type is a struct with kTypeName (the name described on the wire), encode() (appends
// the unpadded body) and a static decode() that checks the exact body size and returns a typed
// Error otherwise. The same shape is used in tracker_messages.hpp, button_messages.hpp and
// force_messages.hpp so Endpoint::send and tests can treat them alike.
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include "device/vrpn/byte_io.hpp"
#include "device/vrpn/error.hpp"

namespace thx::vrpn {

// Client -> server; a server answers with one Pong per local object of that name (a Button server
// also re-sends States). Empty body.
struct Ping {
  static constexpr std::string_view kTypeName = "vrpn_Base ping_message";
  void encode(ByteWriter&) const {}
  static Result<Ping> decode(std::span<const std::uint8_t> payload);
  bool operator==(const Ping&) const = default;
};

struct Pong {
  static constexpr std::string_view kTypeName = "vrpn_Base pong_message";
  void encode(ByteWriter&) const {}
  static Result<Pong> decode(std::span<const std::uint8_t> payload);
  bool operator==(const Pong&) const = default;
};

// uint32 severity, uint32 level, NUL-terminated text. Encoded as the full 8 + 1024 bytes as stock
// senders do (text cut to 1023 bytes); decoded from 8..1032 bytes, text up to the first NUL.
struct TextMessage {
  static constexpr std::string_view kTypeName = "vrpn_Base text_message";
  enum Severity : std::uint32_t { kNormal = 0, kWarning = 1, kError = 2 };
  std::uint32_t severity = kNormal;
  std::uint32_t level = 0;
  std::string text;
  void encode(ByteWriter& w) const;
  static Result<TextMessage> decode(std::span<const std::uint8_t> payload);
  bool operator==(const TextMessage&) const = default;
};

}  // namespace thx::vrpn
