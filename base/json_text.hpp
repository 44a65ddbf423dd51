#pragma once
// JSON string literals for the small JSON files our programs write (statistics, reports).
#include <string>
#include <string_view>

namespace thx::json {

// The text with `"` and `\` escaped and control characters written as \u00XX.
std::string escaped(std::string_view text);
// escaped(text) between double quotes.
std::string quoted(std::string_view text);

}  // namespace thx::json
