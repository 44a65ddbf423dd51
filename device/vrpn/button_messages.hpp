#pragma once
// vrpn_Button messages we use (docs/vrpn.md §8). Same struct shape as base_messages.hpp.
// State values are passed through as sent (stock servers send 0 or 1).
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "device/vrpn/byte_io.hpp"
#include "device/vrpn/error.hpp"

namespace thx::vrpn {

// Server -> client on an edge. Exactly 8 bytes.
struct ButtonChange {
  static constexpr std::string_view kTypeName = "vrpn_Button Change";
  static constexpr std::size_t kSize = 8;
  std::int32_t button = 0;
  std::int32_t state = 0;
  void encode(ByteWriter& w) const;
  static Result<ButtonChange> decode(std::span<const std::uint8_t> payload);
  bool operator==(const ButtonChange&) const = default;
};

// Server -> client on each new connection and after each ping: int32 n, n x int32 state.
// n is limited to kMaxButtons; the body must be exactly 4 + 4n bytes. encode() sends at most
// kMaxButtons states.
struct ButtonStates {
  static constexpr std::string_view kTypeName = "vrpn_Button States";
  std::vector<std::int32_t> states;
  void encode(ByteWriter& w) const;
  static Result<ButtonStates> decode(std::span<const std::uint8_t> payload);
  bool operator==(const ButtonStates&) const = default;
};

}  // namespace thx::vrpn
