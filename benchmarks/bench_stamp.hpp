#pragma once
// When and under what load a benchmark ran: the stamp its results and tables start with.
#include <ctime>
#include <fstream>
#include <string>

namespace thx::bench {

inline std::string isoNow() {
  char buf[32];
  const std::time_t t = std::time(nullptr);
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
  return buf;
}

// The 1, 5 and 15 minute load averages, as /proc/loadavg has them.
inline std::string loadAverage() {
  std::ifstream in("/proc/loadavg");
  std::string a, b, c;
  in >> a >> b >> c;
  return a + " " + b + " " + c;
}

}  // namespace thx::bench
