#include "textures/texture_error.hpp"

namespace thx::tex {

namespace {
std::string format(const std::string& source, const std::string& problem, const std::string& value,
                   const std::string& expected) {
  std::string m = source + ": " + problem;
  if (!value.empty()) m += " (got " + value + ")";
  if (!expected.empty()) m += "; expected " + expected;
  return m;
}
}  // namespace

TextureError::TextureError(std::string source, std::string problem, std::string value, std::string expected)
    : thx::Error(Kind::Config, format(source, problem, value, expected)),
      source_(std::move(source)),
      problem_(std::move(problem)),
      value_(std::move(value)),
      expected_(std::move(expected)) {}

std::string texelName(int i, int j) { return "texel (" + std::to_string(i) + ", " + std::to_string(j) + ")"; }

}  // namespace thx::tex
