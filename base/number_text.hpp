#pragma once
// A number as people read it in a message ("stiffness_fraction = 1.5: expected ..."): printf's
// %g, six significant digits, no trailing zeros. One definition for every error text.
#include <cstdio>
#include <string>

namespace thx {

inline std::string numberText(double value) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", value);
  return buf;
}

}  // namespace thx
