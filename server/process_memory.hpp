#pragma once
// Resident and locked memory of this process, from /proc/self/status (VmRSS, VmLck). Not for the
// real-time thread: it opens a file.
#include <cstdint>

namespace thx::srv {

struct ProcessMemory {
  std::int64_t rss_bytes = 0;
  std::int64_t locked_bytes = 0;
};

ProcessMemory readProcessMemory();

}  // namespace thx::srv
