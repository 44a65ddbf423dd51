#pragma once
// The exact-size rule every stock _Remote applies (docs/vrpn.md §4): one body of the wrong size
// is an error that drops the link. Shared by the fixed-size message decoders.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "device/vrpn/error.hpp"

namespace thx::vrpn {

inline std::optional<Error> checkSize(std::string_view type_name, std::span<const std::uint8_t> payload,
                                      std::size_t expected) {
  if (payload.size() == expected) return std::nullopt;
  return Error{ErrorCode::kPayloadSize, std::string(type_name) + " body is " + std::to_string(payload.size()) +
                                            " bytes, expected " + std::to_string(expected)};
}

}  // namespace thx::vrpn
