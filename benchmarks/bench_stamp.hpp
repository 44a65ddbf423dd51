#pragma once
// When, under what load, on what machine and from which build a benchmark ran: the stamp its
// results and tables start with (docs/report.md shows it as each section's machine line).
#include <sys/utsname.h>

#include <ctime>
#include <fstream>
#include <string>
#include <thread>

namespace thx::bench {

inline std::string isoNow() {
  char buf[32];
  const std::time_t t = std::time(nullptr);
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
  return buf;
}

// The CPU model, the CPUs this process sees, a hypervisor if /proc/cpuinfo's flags name one, and
// the kernel release: "AMD EPYC, 2 CPUs (virtual machine), Linux 6.18.44".
inline std::string machineSummary() {
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string line, model = "unknown CPU";
  bool hypervisor = false, seen_model = false, seen_flags = false;
  while ((!seen_model || !seen_flags) && std::getline(cpuinfo, line)) {
    const std::size_t colon = line.find(':');
    if (colon == std::string::npos) continue;
    const std::size_t start = line.find_first_not_of(" \t", colon + 1);
    const std::string value = start == std::string::npos ? "" : line.substr(start);
    if (!seen_model && line.rfind("model name", 0) == 0) {
      model = value;
      seen_model = true;
    }
    if (!seen_flags && line.rfind("flags", 0) == 0) {
      hypervisor = value.find("hypervisor") != std::string::npos;
      seen_flags = true;
    }
  }
  utsname u{};
  uname(&u);
  return model + ", " + std::to_string(std::thread::hardware_concurrency()) + " CPUs" +
         (hypervisor ? " (virtual machine)" : "") + ", Linux " + u.release;
}

// The CMake build type the benchmark was compiled in (THX_BUILD_TYPE, defined in
// benchmarks/CMakeLists.txt for the benchmarks that stamp it; the report's machine line shows it).
inline const char* buildType() {
#ifdef THX_BUILD_TYPE
  return THX_BUILD_TYPE[0] != '\0' ? THX_BUILD_TYPE : "none";
#else
  return "not set";
#endif
}

// The 1, 5 and 15 minute load averages, as /proc/loadavg has them.
inline std::string loadAverage() {
  std::ifstream in("/proc/loadavg");
  std::string a, b, c;
  in >> a >> b >> c;
  return a + " " + b + " " + c;
}

}  // namespace thx::bench
