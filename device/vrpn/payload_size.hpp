#pragma once
// The exact-size rule every stock _Remote applies (docs/vrpn.md §4): one body of the wrong size
// is an error that drops the link. Shared by the fixed-size message decoders.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>

#include "device/vrpn/error.hpp"

namespace thx::vrpn {

// "NAME body is N bytes, expected WHAT". Appended piece by piece: g++ 12 at -O2 reports a chain
// of std::string operator+ here as an out-of-bounds memcpy (a false positive; docs/build.md).
inline Error sizeError(std::string_view type_name, std::size_t got, std::string_view expected) {
  std::string m(type_name);
  m.append(" body is ").append(std::to_string(got)).append(" bytes, expected ").append(expected);
  return Error{ErrorCode::kPayloadSize, std::move(m)};
}

inline std::optional<Error> checkSize(std::string_view type_name, std::span<const std::uint8_t> payload,
                                      std::size_t expected) {
  if (payload.size() == expected) return std::nullopt;
  return sizeError(type_name, payload.size(), std::to_string(expected));
}

}  // namespace thx::vrpn
