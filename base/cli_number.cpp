#include "base/cli_number.hpp"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "base/error.hpp"

namespace thx::cli {

namespace {
std::string rangeText(const Range& r) {
  char b[96];
  if (r.min <= -1e300 && r.max >= 1e300) return "a number";
  std::snprintf(b, sizeof b, "a number in %s%g, %g]", r.min_open ? "(" : "[", r.min, r.max);
  return std::string(b) + (r.unit.empty() ? "" : " " + std::string(r.unit));
}
}  // namespace

double parseNumber(std::string_view option, std::string_view text, const Range& range) {
  const std::string s(text);
  char* end = nullptr;
  const double v = std::strtod(s.c_str(), &end);
  const bool parsed = !s.empty() && end != nullptr && *end == '\0' && std::isfinite(v);
  if (!parsed || v > range.max || v < range.min || (range.min_open && v == range.min))
    throw UsageError(std::string(option) + ": expected " + rangeText(range) + ", got '" + s + "'");
  return v;
}

long long parseInteger(std::string_view option, std::string_view text, long long min, long long max) {
  const std::string s(text);
  char* end = nullptr;
  errno = 0;
  const long long v = std::strtoll(s.c_str(), &end, 10);
  if (s.empty() || end == nullptr || *end != '\0' || errno == ERANGE || v < min || v > max)
    throw UsageError(std::string(option) + ": expected a whole number in [" + std::to_string(min) + ", " +
                     std::to_string(max) + "], got '" + s + "'");
  return v;
}

namespace {

// Each comma-separated item of text, read by `read`.
template <class T, class Read>
std::vector<T> parseList(std::string_view text, Read read) {
  std::vector<T> out;
  for (std::size_t a = 0; a <= text.size();) {
    std::size_t b = text.find(',', a);
    if (b == std::string_view::npos) b = text.size();
    out.push_back(read(text.substr(a, b - a)));
    a = b + 1;
  }
  return out;
}

}  // namespace

std::vector<int> parseIntegerList(std::string_view option, std::string_view text, int min, int max) {
  return parseList<int>(text, [&](std::string_view item) { return int(parseInteger(option, item, min, max)); });
}

std::vector<double> parseNumberList(std::string_view option, std::string_view text, const Range& range) {
  return parseList<double>(text, [&](std::string_view item) { return parseNumber(option, item, range); });
}

}  // namespace thx::cli
