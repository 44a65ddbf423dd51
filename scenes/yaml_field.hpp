#pragma once
// A YAML node together with where it sits: the file, its line and column, and its field path
// ("objects[2].radius"). Every reader checks type, finiteness and range and throws SceneError
// naming all of those, so the section parsers only say what each field must be.
//
// A null value (`key:` with nothing after it) of a mapping or a sequence reads as empty, so
// `objects:` alone means no objects; a null scalar is an error ("missing value").
#include <yaml-cpp/yaml.h>

#include <Eigen/Core>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "scenes/closest_match.hpp"
#include "scenes/scene_error.hpp"

namespace thx::scene {

struct Material;

struct ParseContext {
  std::string source;    // file name for messages
  std::string base_dir;  // relative paths resolve against this ("" = current directory)
  std::vector<std::string>* warnings = nullptr;
  // The scene's own materials (top-level `materials:`), read before any section that names one.
  const std::vector<Material>* custom_materials = nullptr;
};

struct NumberRange {
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool min_inclusive = true;
  bool max_inclusive = true;
  std::string unit;  // "m", "N", "N·s/m" ... shown in messages

  bool contains(double x) const;
  std::string describe() const;  // "a number in (0, 10] m"
};
NumberRange closedRange(double min, double max, std::string unit);
NumberRange positiveUpTo(double max, std::string unit);  // (0, max]

// Shortest text that reads back to the same double ("0.6", "1e-05").
std::string formatNumber(double x);

class Field {
 public:
  Field(const ParseContext& context, YAML::Node node, std::string path, YAML::Mark key_mark);
  static Field root(const ParseContext& context, const YAML::Node& node);
  Field(const Field&) = default;
  // YAML::Node's assignment writes through to the document instead of rebinding, so a Field
  // is never reassigned (use std::optional<Field>::emplace).
  Field& operator=(const Field&) = delete;

  const std::string& path() const { return path_; }
  const ParseContext& context() const { return *context_; }
  bool isNull() const { return node_.IsNull(); }
  bool isMapping() const { return node_.IsMap(); }
  // Where the value is; for a null value, where its key is (yaml-cpp marks an empty value at the
  // next token, often on the following line).
  SourceLocation location() const;
  // Where the key is: for errors about the field as a whole ("does not apply here").
  SourceLocation keyLocation() const;
  // "'abc'", "a mapping", "a sequence of 3 items", "nothing (null)".
  std::string describeValue() const;

  [[noreturn]] void fail(const std::string& problem, const std::string& expected, const std::string& value) const;
  // The value shown is this field's own.
  [[noreturn]] void fail(const std::string& problem, const std::string& expected) const;
  void warn(const std::string& message) const;

  // Scalars.
  double number(const NumberRange& range) const;
  long long integer(long long min, long long max, const std::string& unit = {}) const;
  std::uint64_t unsignedInteger() const;
  std::string text() const;  // a non-empty scalar
  template <class E>
  E choice(const std::vector<std::pair<std::string, E>>& options) const;
  // Sequences of exactly N numbers, each within `range`; `layout` is e.g. "[x, y]".
  Eigen::Vector2d vector2(const NumberRange& range, const std::string& layout = "[x, y]") const;
  Eigen::Vector3d vector3(const NumberRange& range, const std::string& layout = "[x, y, z]") const;

  // Mappings. expectKeys() rejects non-mappings, duplicate keys and unknown keys (naming the
  // closest valid one); call it before find()/at().
  void expectKeys(const std::vector<std::string>& allowed) const;
  bool has(std::string_view key) const { return find(key).has_value(); }
  std::optional<Field> find(std::string_view key) const;
  Field at(std::string_view key, const std::string& expected) const;  // required
  // A stand-in for a key that is not there, located at the key owning this mapping, for
  // "missing" errors with a problem of the caller's own wording.
  Field absent(std::string_view key) const;
  std::vector<std::pair<std::string, Field>> entries() const;

  // Sequences.
  std::vector<Field> items() const;

  // Relative paths resolve against the scene file's directory.
  std::string resolvePath(const std::string& written) const;

 private:
  std::vector<double> numbers(std::size_t count, const NumberRange& range, const std::string& layout) const;
  void expectScalar(const std::string& expected) const;

  const ParseContext* context_;
  YAML::Node node_;
  std::string path_;
  YAML::Mark key_mark_;
};

template <class E>
E Field::choice(const std::vector<std::pair<std::string, E>>& options) const {
  std::vector<std::string> names;
  for (const auto& [name, value] : options) names.push_back(name);
  expectScalar("one of: " + joinNames(names));
  const std::string& s = node_.Scalar();
  for (const auto& [name, value] : options)
    if (name == s) return value;
  const std::string guess = closestMatch(s, names);
  fail(guess.empty() ? "unknown value" : "unknown value (did you mean '" + guess + "'?)", "one of: " + joinNames(names),
       describeValue());
}

}  // namespace thx::scene
