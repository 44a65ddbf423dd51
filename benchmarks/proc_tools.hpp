#pragma once
// Process helpers for the memory, latency and client benchmarks: watch a program through /proc.
// Starting, waiting for and reading back programs is the tests' (tests/support/process.hpp,
// tests/support/flat_json.hpp, included here). Linux only.
#include <sys/types.h>

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "tests/support/flat_json.hpp"
#include "tests/support/process.hpp"

namespace thx::bench {

// Starts argv[0] (looked up in PATH if it has no '/') with stdout and stderr appended to
// log_path. Throws std::runtime_error if fork fails; an exec failure shows as exit status 127.
inline pid_t spawn(const std::vector<std::string>& argv, const std::string& log_path) {
  return test::spawnIn("", argv, log_path, log_path, /*append=*/true);
}

// /proc/<pid>/smaps, one entry per mapping (sizes in bytes).
struct Mapping {
  std::uint64_t start = 0, end = 0;
  std::string perms, path;
  std::int64_t size = 0, rss = 0, pss = 0, locked = 0, anonymous = 0;
};
std::vector<Mapping> readSmaps(pid_t pid);
// A field of /proc/<pid>/status in bytes (for "kB" fields) or as a plain number; -1 if absent.
std::int64_t statusField(pid_t pid, const std::string& key);
// Scheduling policy of each thread of pid (0 other, 1 FIFO, 2 RR, ...), from /proc/<pid>/task/*/stat.
std::map<int, int> threadPolicies(pid_t pid);
// Thread names (comm) by tid.
std::map<int, std::string> threadNames(pid_t pid);

}  // namespace thx::bench
