#include "server/process_memory.hpp"

#include <cstdio>
#include <cstring>

namespace thx::srv {

ProcessMemory readProcessMemory() {
  ProcessMemory m;
  std::FILE* f = std::fopen("/proc/self/status", "r");
  if (!f) return m;
  char line[256];
  while (std::fgets(line, sizeof line, f)) {
    long long kib = 0;
    if (std::sscanf(line, "VmRSS: %lld kB", &kib) == 1) m.rss_bytes = kib * 1024;
    if (std::sscanf(line, "VmLck: %lld kB", &kib) == 1) m.locked_bytes = kib * 1024;
  }
  std::fclose(f);
  return m;
}

}  // namespace thx::srv
