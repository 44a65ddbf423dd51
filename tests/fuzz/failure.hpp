#pragma once
// What every fuzz body returns and how it checks a refusal's message: shared by the bodies (built
// into the libFuzzer targets, so no GoogleTest here) and the short run (short_run.hpp).
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace thx::fuzz {

using Bytes = std::vector<std::uint8_t>;
// The description of the first broken property, or nothing.
using Failure = std::optional<std::string>;
using Body = Failure (*)(std::span<const std::uint8_t>);

// A refused input's message must say which input it was.
inline Failure mustName(const std::string& message, const std::string& source, const char* what) {
  if (message.find(source) == std::string::npos) return std::string(what) + " does not name '" + source + "': " + message;
  return std::nullopt;
}

}  // namespace thx::fuzz
