#pragma once
// Process helpers for the memory and latency benchmarks: start a program, watch it through
// /proc, read back the small JSON files hapticd writes. Linux only.
#include <sys/types.h>

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace thx::bench {

// Starts argv[0] (looked up in PATH if it has no '/') with stdout and stderr appended to
// log_path. Throws std::runtime_error if fork fails; an exec failure shows as exit status 127.
pid_t spawn(const std::vector<std::string>& argv, const std::string& log_path);
// Non-blocking: the exit status if the child has ended (then it is reaped), else nullopt.
std::optional<int> poll(pid_t pid);
int waitFor(pid_t pid);  // blocking; the exit status (128 + signal if killed)
std::string commandLine(const std::vector<std::string>& argv);

std::string readFile(const std::string& path);  // "" if unreadable

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

// Minimal reader for the flat JSON hapticd writes: the number after "key": inside the object
// that follows "object": (or at top level when object is empty). nullopt if absent.
std::optional<double> jsonNumber(const std::string& text, const std::string& object, const std::string& key);
std::optional<bool> jsonBool(const std::string& text, const std::string& object, const std::string& key);

}  // namespace thx::bench
