// HandScript::loadPathCsv: recorded hand paths, `t_s, x_m, y_m, force_n` (docs/scenes.md).
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <string_view>

#include "device/hand_script.hpp"
#include "device/hand_script_detail.hpp"

namespace thx::dev {

namespace detail {

std::string formatNumber(double v) {
  std::array<char, 32> buf{};
  const auto res = std::to_chars(buf.data(), buf.data() + buf.size(), v);
  return std::string(buf.data(), res.ptr);
}

}  // namespace detail

namespace {

constexpr std::array<const char*, 4> kColumns = {"t_s", "x_m", "y_m", "force_n"};
constexpr std::array<const char*, 4> kExpected = {"a time >= 0 s", "a position in m", "a position in m",
                                                  "a force >= 0 N"};

std::string_view trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

bool parseNumber(std::string_view s, double& out) {
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  if (s.empty()) return false;
  const auto res = std::from_chars(s.data(), s.data() + s.size(), out);
  return res.ec == std::errc() && res.ptr == s.data() + s.size();
}

bool equalsIgnoreCase(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(a[i])) != std::tolower(static_cast<unsigned char>(b[i]))) return false;
  return true;
}

struct Fail {
  const std::string& file;
  int line;
  [[noreturn]] void operator()(const std::string& field, const std::string& problem, const std::string& expected,
                               std::string_view value) const {
    throw HandScriptError(file + ":" + std::to_string(line) + ": " + field + ": " + problem + "; expected " +
                              expected + ", got '" + std::string(value) + "'",
                          file, line, field);
  }
};

}  // namespace

HandPath HandScript::loadPathCsv(const std::string& path) {
  std::ifstream in(path);
  if (!in)
    throw HandScriptError(
        path + ": cannot open the path file; expected a readable CSV file with rows t_s, x_m, y_m, force_n", path, 0, "");
  HandPath result;
  result.source = path;
  std::string text;
  int line_no = 0;
  bool first_content_line = true;
  while (std::getline(in, text)) {
    ++line_no;
    std::string_view line(text);
    if (const std::size_t hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
    line = trim(line);
    if (line.empty()) continue;
    const Fail fail{path, line_no};

    std::array<std::string_view, 4> fields{};
    std::size_t count = 0;
    for (std::string_view rest = line;;) {
      const std::size_t comma = rest.find(',');
      if (count < fields.size()) fields[count] = trim(rest.substr(0, comma));
      ++count;
      if (comma == std::string_view::npos) break;
      rest = rest.substr(comma + 1);
    }

    double first_value = 0.0;
    if (first_content_line && !parseNumber(fields[0], first_value)) {
      // The only non-numeric line allowed is the header, and only as the first line.
      bool is_header = count == kColumns.size();
      for (std::size_t i = 0; is_header && i < kColumns.size(); ++i)
        is_header = equalsIgnoreCase(fields[i], kColumns[i]);
      if (!is_header)
        fail("header", "not a header or a data row", "the header 't_s, x_m, y_m, force_n' or numbers", line);
      first_content_line = false;
      continue;
    }
    first_content_line = false;

    if (count != kColumns.size())
      fail("row", "wrong number of fields", "4 fields t_s, x_m, y_m, force_n", std::to_string(count) + " fields");
    std::array<double, 4> v{};
    for (std::size_t i = 0; i < kColumns.size(); ++i) {
      if (!parseNumber(fields[i], v[i])) fail(kColumns[i], "not a number", kExpected[i], fields[i]);
      if (!std::isfinite(v[i])) fail(kColumns[i], "not finite", kExpected[i], fields[i]);
    }
    if (v[0] < 0.0) fail("t_s", "out of range", kExpected[0], fields[0]);
    if (!result.samples.empty() && !(v[0] > result.samples.back().t_s))
      fail("t_s", "time does not increase",
           "a time > " + detail::formatNumber(result.samples.back().t_s) + " s (the previous row's)", fields[0]);
    if (v[3] < 0.0) fail("force_n", "out of range", kExpected[3], fields[3]);
    result.samples.push_back(PathSample{v[0], Eigen::Vector2d(v[1], v[2]), v[3]});
  }
  if (result.samples.size() < 2)
    throw HandScriptError(path + ": samples: too few samples; expected at least 2 rows t_s, x_m, y_m, force_n, got " +
                              std::to_string(result.samples.size()),
                          path, 0, "samples");
  return result;
}

}  // namespace thx::dev
