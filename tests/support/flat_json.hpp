#pragma once
// Readers for the small flat JSON files our programs write (hapticd --stats-json, probe-client
// and physics-client --json): enough for tests and benchmarks, not a JSON parser.
#include <cmath>
#include <cstdlib>
#include <optional>
#include <regex>
#include <string>

namespace thx::test {

// The value after the first "key": anywhere in the text; strings without their quotes.
// "<missing KEY>" when absent.
inline std::string jsonField(const std::string& json, const std::string& key) {
  const std::regex text("\"" + key + "\": \"([^\"]*)\"");
  const std::regex number("\"" + key + "\": ([^,}\n]*)");
  std::smatch m;
  if (std::regex_search(json, m, text) || std::regex_search(json, m, number)) return m[1].str();
  return "<missing " + key + ">";
}

// jsonField() as a number; NaN when absent or not a number.
inline double jsonNumber(const std::string& json, const std::string& key) {
  try {
    return std::stod(jsonField(json, key));
  } catch (...) {
    return NAN;
  }
}

namespace detail {
// Where the value of "key" starts inside the object that follows "object": (or at the top level
// when object is empty).
inline std::optional<std::size_t> valueStart(const std::string& text, const std::string& object,
                                             const std::string& key) {
  std::size_t from = 0, to = text.size();
  if (!object.empty()) {
    // The key "object" followed by ':' (a string value "object" does not count).
    const std::string quoted = "\"" + object + "\"";
    std::size_t o = text.find(quoted);
    while (o != std::string::npos) {
      const std::size_t next = text.find_first_not_of(" \t\r\n", o + quoted.size());
      if (next != std::string::npos && text[next] == ':') break;
      o = text.find(quoted, o + 1);
    }
    if (o == std::string::npos) return std::nullopt;
    from = text.find('{', o);
    if (from == std::string::npos) return std::nullopt;
    to = text.find('}', from);
    if (to == std::string::npos) return std::nullopt;
  }
  const std::string needle = "\"" + key + "\"";
  std::size_t k = text.find(needle, from);
  // At top level, skip matches inside nested objects by requiring brace depth 1.
  while (k != std::string::npos && k < to) {
    int depth = 0;
    for (std::size_t i = from; i < k; ++i) depth += text[i] == '{' ? 1 : (text[i] == '}' ? -1 : 0);
    if (object.empty() ? depth == 1 : true) break;
    k = text.find(needle, k + 1);
  }
  if (k == std::string::npos || k >= to) return std::nullopt;
  const std::size_t colon = text.find(':', k + needle.size());
  if (colon == std::string::npos) return std::nullopt;
  const std::size_t v = text.find_first_not_of(" \t\r\n", colon + 1);
  if (v == std::string::npos) return std::nullopt;
  return v;
}
}  // namespace detail

// The number after "key": inside the object that follows "object": (at the top level when object
// is empty); nullopt if absent.
inline std::optional<double> jsonNumber(const std::string& text, const std::string& object, const std::string& key) {
  const auto s = detail::valueStart(text, object, key);
  if (!s) return std::nullopt;
  char* end = nullptr;
  const double v = std::strtod(text.c_str() + *s, &end);
  if (end == text.c_str() + *s) return std::nullopt;
  return v;
}

inline std::optional<bool> jsonBool(const std::string& text, const std::string& object, const std::string& key) {
  const auto s = detail::valueStart(text, object, key);
  if (!s) return std::nullopt;
  if (text.compare(*s, 4, "true") == 0) return true;
  if (text.compare(*s, 5, "false") == 0) return false;
  return std::nullopt;
}

}  // namespace thx::test
