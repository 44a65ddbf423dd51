#pragma once
// What a call throws, as text: tests compare error messages a user would read.
#include <functional>
#include <string>

#include "base/error.hpp"

namespace thx::test {

// The thx::Error f() throws, its what(); "<no thx::Error>" when it throws none.
inline std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const thx::Error& e) {
    return e.what();
  }
  return "<no thx::Error>";
}

}  // namespace thx::test
