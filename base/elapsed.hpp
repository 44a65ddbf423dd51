#pragma once
// Wall time since a steady-clock instant, in seconds: what progress lines and benchmarks print.
#include <chrono>

namespace thx {

inline double secondsSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace thx
