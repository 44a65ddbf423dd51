#include "scenes/yaml_field.hpp"

#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <filesystem>

namespace thx::scene {

namespace {

enum class NumberParse { Ok, NotANumber, NotFinite };

// YAML 1.2 core-schema floats, strictly: the whole scalar must be the number. yaml-cpp's own
// conversion would also accept it, but we need to tell "not a number" from ".nan"/".inf".
NumberParse parseNumber(std::string_view s, double& out) {
  if (s == ".nan" || s == ".NaN" || s == ".NAN" || s == ".inf" || s == ".Inf" || s == ".INF" || s == "-.inf" ||
      s == "-.Inf" || s == "-.INF" || s == "+.inf" || s == "+.Inf" || s == "+.INF")
    return NumberParse::NotFinite;
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  if (s.empty()) return NumberParse::NotANumber;
  const char first = s.front() == '-' && s.size() > 1 ? s[1] : s.front();
  // from_chars would read "inf"/"nan" too; YAML spells those with a dot, handled above.
  if (!(std::isdigit(static_cast<unsigned char>(first)) || first == '.')) return NumberParse::NotANumber;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), out, std::chars_format::general);
  if (end != s.data() + s.size()) return NumberParse::NotANumber;
  if (ec == std::errc::result_out_of_range) {
    // Overflow is not finite; underflow (1e-400) is a legitimate, if silly, zero.
    out = std::strtod(std::string(s).c_str(), nullptr);
    return std::isfinite(out) ? NumberParse::Ok : NumberParse::NotFinite;
  }
  if (ec != std::errc()) return NumberParse::NotANumber;
  return std::isfinite(out) ? NumberParse::Ok : NumberParse::NotFinite;
}

std::string quote(const std::string& s) {
  constexpr std::size_t kMaxShown = 60;
  if (s.size() <= kMaxShown) return "'" + s + "'";
  return "'" + s.substr(0, kMaxShown) + "...'";
}

std::string childPath(const std::string& parent, std::string_view key) {
  return parent.empty() ? std::string(key) : parent + "." + std::string(key);
}

}  // namespace

bool NumberRange::contains(double x) const {
  const bool above = min_inclusive ? x >= min : x > min;
  const bool below = max_inclusive ? x <= max : x < max;
  return above && below;
}

std::string NumberRange::describe() const {
  const bool has_min = std::isfinite(min), has_max = std::isfinite(max);
  std::string s;
  if (has_min && has_max) {
    s = std::string("a number in ") + (min_inclusive ? "[" : "(") + formatNumber(min) + ", " + formatNumber(max) +
        (max_inclusive ? "]" : ")");
  } else if (has_min) {
    s = std::string("a number ") + (min_inclusive ? ">= " : "> ") + formatNumber(min);
  } else if (has_max) {
    s = std::string("a number ") + (max_inclusive ? "<= " : "< ") + formatNumber(max);
  } else {
    s = "a finite number";
  }
  if (!unit.empty()) s += " " + unit;
  return s;
}

NumberRange closedRange(double min, double max, std::string unit) { return {min, max, true, true, std::move(unit)}; }
NumberRange positiveUpTo(double max, std::string unit) { return {0.0, max, false, true, std::move(unit)}; }

std::string formatNumber(double x) {
  char buffer[64];
  const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, x);
  return ec == std::errc() ? std::string(buffer, end) : std::string("?");
}

Field::Field(const ParseContext& context, YAML::Node node, std::string path, YAML::Mark key_mark)
    : context_(&context), node_(std::move(node)), path_(std::move(path)), key_mark_(key_mark) {}

Field Field::root(const ParseContext& context, const YAML::Node& node) {
  return Field(context, node, "", YAML::Mark());
}

SourceLocation Field::location() const {
  YAML::Mark m = key_mark_;
  if (!node_.IsNull() && !node_.Mark().is_null()) m = node_.Mark();
  if (m.is_null()) return {context_->source, 0, 0};
  return {context_->source, m.line + 1, m.column + 1};
}

SourceLocation Field::keyLocation() const {
  if (key_mark_.is_null()) return location();
  return {context_->source, key_mark_.line + 1, key_mark_.column + 1};
}

std::string Field::describeValue() const {
  if (node_.IsNull()) return "nothing (null)";
  if (node_.IsScalar()) return quote(node_.Scalar());
  if (node_.IsMap()) return "a mapping";
  if (node_.IsSequence()) {
    const std::size_t n = node_.size();
    return "a sequence of " + std::to_string(n) + (n == 1 ? " item" : " items");
  }
  return "an undefined value";
}

void Field::fail(const std::string& problem, const std::string& expected, const std::string& value) const {
  throw SceneError(location(), path_, problem, expected, value);
}

void Field::fail(const std::string& problem, const std::string& expected) const {
  fail(problem, expected, describeValue());
}

void Field::warn(const std::string& message) const {
  if (context_->warnings == nullptr) return;
  std::string w = toString(location()) + ": ";
  if (!path_.empty()) w += path_ + ": ";
  context_->warnings->push_back(w + message);
}

void Field::expectScalar(const std::string& expected) const {
  if (node_.IsNull()) fail("missing value", expected);
  if (!node_.IsScalar()) fail("wrong type", expected);
}

double Field::number(const NumberRange& range) const {
  expectScalar(range.describe());
  double x = 0.0;
  switch (parseNumber(node_.Scalar(), x)) {
    case NumberParse::NotANumber:
      fail("wrong type", range.describe());
    case NumberParse::NotFinite:
      fail("not a finite number", range.describe());
    case NumberParse::Ok:
      break;
  }
  if (!range.contains(x)) fail("out of range", range.describe());
  return x;
}

long long Field::integer(long long min, long long max, const std::string& unit) const {
  std::string expected = "an integer in [" + std::to_string(min) + ", " + std::to_string(max) + "]";
  if (!unit.empty()) expected += " " + unit;
  expectScalar(expected);
  const std::string& s = node_.Scalar();
  long long value = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
  if (ec != std::errc() || end != s.data() + s.size()) {
    // Also accept integral floats such as 1e4 (a natural way to write 10 kHz).
    double x = 0.0;
    const NumberParse parsed = parseNumber(s, x);
    if (parsed == NumberParse::NotFinite) fail("not a finite number", expected);
    if (parsed != NumberParse::Ok) fail("wrong type", expected);
    if (x != std::floor(x)) fail("not an integer", expected);
    if (x < double(min) || x > double(max)) fail("out of range", expected);
    value = static_cast<long long>(x);
  }
  if (value < min || value > max) fail("out of range", expected);
  return value;
}

std::uint64_t Field::unsignedInteger() const {
  const std::string expected = "an integer in [0, 18446744073709551615]";
  expectScalar(expected);
  std::string_view s = node_.Scalar();
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  double negative = 0.0;
  if (!s.empty() && s.front() == '-' && parseNumber(s, negative) == NumberParse::Ok) fail("out of range", expected);
  std::uint64_t value = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
  if (ec == std::errc::result_out_of_range) fail("out of range", expected);
  if (ec != std::errc() || end != s.data() + s.size()) fail("wrong type", expected);
  return value;
}

std::string Field::text() const {
  expectScalar("a non-empty string");
  if (node_.Scalar().empty()) fail("empty string", "a non-empty string");
  return node_.Scalar();
}

std::vector<double> Field::numbers(std::size_t count, const NumberRange& range, const std::string& layout) const {
  const std::string expected = "a sequence of " + std::to_string(count) + " numbers " + layout;
  if (node_.IsNull()) fail("missing value", expected);
  if (!node_.IsSequence()) fail("wrong type", expected);
  if (node_.size() != count) fail("wrong length", expected);
  std::vector<double> values;
  for (const Field& item : items()) values.push_back(item.number(range));
  return values;
}

Eigen::Vector2d Field::vector2(const NumberRange& range, const std::string& layout) const {
  const std::vector<double> v = numbers(2, range, layout);
  return {v[0], v[1]};
}

Eigen::Vector3d Field::vector3(const NumberRange& range, const std::string& layout) const {
  const std::vector<double> v = numbers(3, range, layout);
  return {v[0], v[1], v[2]};
}

void Field::expectKeys(const std::vector<std::string>& allowed) const {
  const std::string expected = "a mapping with fields " + joinNames(allowed);
  if (node_.IsNull()) return;
  if (!node_.IsMap()) fail("wrong type", expected);
  std::vector<std::pair<std::string, int>> seen;  // key, line
  for (auto it = node_.begin(); it != node_.end(); ++it) {
    const Field key(*context_, it->first, path_, it->first.Mark());
    if (!it->first.IsScalar()) key.fail("field name is not a plain word", expected);
    const std::string& name = it->first.Scalar();
    const Field named(*context_, it->first, childPath(path_, name), it->first.Mark());
    for (const auto& [other, line] : seen)
      if (other == name)
        named.fail("duplicate field (first given on line " + std::to_string(line) + ")", "each field once");
    seen.emplace_back(name, it->first.Mark().line + 1);
    if (std::find(allowed.begin(), allowed.end(), name) == allowed.end()) {
      const std::string guess = closestMatch(name, allowed);
      named.fail(guess.empty() ? "unknown field '" + name + "'"
                               : "unknown field '" + name + "' (did you mean '" + guess + "'?)",
                 "one of: " + joinNames(allowed), "");
    }
  }
}

std::optional<Field> Field::find(std::string_view key) const {
  if (!node_.IsMap()) return std::nullopt;
  for (auto it = node_.begin(); it != node_.end(); ++it)
    if (it->first.IsScalar() && it->first.Scalar() == key)
      return Field(*context_, it->second, childPath(path_, key), it->first.Mark());
  return std::nullopt;
}

Field Field::at(std::string_view key, const std::string& expected) const {
  if (auto f = find(key)) return *f;
  absent(key).fail("missing required field", expected, "");
}

Field Field::absent(std::string_view key) const {
  // Point at the key that owns this mapping (e.g. the `surface:` line), where the field belongs.
  return Field(*context_, YAML::Node(), childPath(path_, key), key_mark_.is_null() ? node_.Mark() : key_mark_);
}

std::vector<std::pair<std::string, Field>> Field::entries() const {
  std::vector<std::pair<std::string, Field>> out;
  if (!node_.IsMap()) return out;
  for (auto it = node_.begin(); it != node_.end(); ++it) {
    const std::string name = it->first.IsScalar() ? it->first.Scalar() : std::string("?");
    out.emplace_back(name, Field(*context_, it->second, childPath(path_, name), it->first.Mark()));
  }
  return out;
}

std::vector<Field> Field::items() const {
  std::vector<Field> out;
  if (node_.IsNull()) return out;
  if (!node_.IsSequence()) fail("wrong type", "a sequence (a list of '- item' lines or [a, b])");
  std::size_t i = 0;
  for (auto it = node_.begin(); it != node_.end(); ++it, ++i)
    out.emplace_back(*context_, *it, path_ + "[" + std::to_string(i) + "]", it->Mark());
  return out;
}

std::string Field::resolvePath(const std::string& written) const {
  const std::filesystem::path p(written);
  if (p.is_absolute() || context_->base_dir.empty()) return p.lexically_normal().string();
  return (std::filesystem::path(context_->base_dir) / p).lexically_normal().string();
}

}  // namespace thx::scene
