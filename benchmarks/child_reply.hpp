#pragma once
// Shared by the benchmarks that run a solve in a child process so that its peak resident set is
// its own (bench_audio_fem, bench_table1): read everything the child writes to a pipe, then reap
// it with wait4 for its exit status and ru_maxrss.
#include <sys/types.h>

#include <string>

namespace thx::bench {

struct ChildReply {
  std::string text;      // all the child wrote
  long peak_rss_kb = 0;  // its peak resident set (wait4's ru_maxrss)
  int status = 0;        // as waitpid reports it
  bool reaped = false;   // false if wait4 failed
};

// Reads `read_fd` to its end, closes it, and waits for `pid`.
ChildReply readChildReply(pid_t pid, int read_fd);

}  // namespace thx::bench
