#include "scenes/scene_error.hpp"

namespace thx::scene {

std::string toString(const SourceLocation& where) {
  std::string s = where.file.empty() ? std::string("<scene>") : where.file;
  if (where.line > 0) {
    s += ':' + std::to_string(where.line);
    if (where.column > 0) s += ':' + std::to_string(where.column);
  }
  return s;
}

namespace {
std::string format(const SourceLocation& where, const std::string& field, const std::string& problem,
                   const std::string& expected, const std::string& value) {
  std::string m = toString(where) + ": ";
  if (!field.empty()) m += field + ": ";
  m += problem;
  if (!expected.empty()) m += "; expected " + expected;
  if (!value.empty()) m += (expected.empty() ? "; got " : ", got ") + value;
  return m;
}
}  // namespace

SceneError::SceneError(SourceLocation where, std::string field, std::string problem, std::string expected,
                       std::string value)
    : thx::Error(Kind::Config, format(where, field, problem, expected, value)),
      where_(std::move(where)),
      field_(std::move(field)),
      problem_(std::move(problem)),
      expected_(std::move(expected)),
      value_(std::move(value)) {}

}  // namespace thx::scene
