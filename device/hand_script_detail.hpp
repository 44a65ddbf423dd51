#pragma once
// Internals shared by hand_script.cpp and hand_path_csv.cpp (not part of the public API).
#include <string>

namespace thx::dev::detail {

// Shortest round-trip text of a number, for error messages ("0.1", "-inf", "nan").
std::string formatNumber(double v);

}  // namespace thx::dev::detail
