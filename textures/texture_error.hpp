#pragma once
// One error type for every texture problem. The message always names the file (or the in-memory
// source), the problem, the offending value and what was expected, so a user can fix the input
// without reading code.
#include <string>

#include "base/error.hpp"

namespace thx::tex {

class TextureError : public thx::Error {
 public:
  TextureError(std::string source, std::string problem, std::string value, std::string expected);

  const std::string& source() const { return source_; }
  const std::string& problem() const { return problem_; }
  const std::string& value() const { return value_; }
  const std::string& expected() const { return expected_; }

 private:
  std::string source_, problem_, value_, expected_;
};

// "texel (i, j)", as every texture message names a texel.
std::string texelName(int i, int j);

}  // namespace thx::tex
