#include "benchmarks/child_reply.hpp"

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

namespace thx::bench {

ChildReply readChildReply(pid_t pid, int read_fd) {
  ChildReply r;
  char buf[512];
  for (ssize_t n; (n = read(read_fd, buf, sizeof buf)) > 0;) r.text.append(buf, std::size_t(n));
  close(read_fd);
  rusage usage{};
  r.reaped = pid > 0 && wait4(pid, &r.status, 0, &usage) == pid;
  r.peak_rss_kb = usage.ru_maxrss;
  return r;
}

}  // namespace thx::bench
