#pragma once
// One error type for every scene problem. The message names the file, the line and column, the
// field path (e.g. `surface.texture.params.mortar_width`), the problem, the offending value and
// what was expected, so a user can fix the scene without reading code:
//
//   scenes/x.yaml:7:12: surface.size[1]: wrong type; expected a number in (0, 10] m, got 'abc'
#include <string>

#include "base/error.hpp"

namespace thx::scene {

// Where something is in a scene file. Line and column are 1-based; 0 means unknown (for example
// a file that could not be opened at all).
struct SourceLocation {
  std::string file;
  int line = 0;
  int column = 0;
};

// "file:line:column" (or just "file" when the line is unknown).
std::string toString(const SourceLocation& where);

class SceneError : public thx::Error {
 public:
  SceneError(SourceLocation where, std::string field, std::string problem, std::string expected = {},
             std::string value = {});

  const SourceLocation& where() const { return where_; }
  const std::string& field() const { return field_; }
  const std::string& problem() const { return problem_; }
  const std::string& expected() const { return expected_; }
  const std::string& value() const { return value_; }

 private:
  SourceLocation where_;
  std::string field_, problem_, expected_, value_;
};

}  // namespace thx::scene
