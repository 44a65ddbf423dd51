#pragma once
// Child processes for the tests that run hapticd and its clients as a user would, and for the
// benchmarks that measure them: start one with its output in files, poll, wait or reap it with a
// time limit, read back what it wrote. No GoogleTest here (the benchmarks use it too); the gtest
// fixture for hapticd is hapticd_harness.hpp. Linux only.
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace thx::test {

// The whole file; "" if it cannot be read.
inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

// fork + exec argv (argv[0] looked up in PATH when it has no '/') in `cwd` (unless empty), with
// stdout to `out` and stderr to `err` (one file when they are the same; appended to when
// `append`, else truncated) and stdin from /dev/null. Throws std::runtime_error if fork fails; a
// child that cannot change directory or open its files exits 126, one that cannot exec 127.
inline pid_t spawnIn(const std::string& cwd, const std::vector<std::string>& argv, const std::string& out,
                     const std::string& err, bool append = false) {
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  std::fflush(nullptr);
  const pid_t pid = fork();
  if (pid < 0) throw std::runtime_error(std::string("fork: ") + std::strerror(errno));
  if (pid != 0) return pid;
  const int mode = O_WRONLY | O_CREAT | (append ? O_APPEND : O_TRUNC);
  const int o = open(out.c_str(), mode, 0644);
  const int e = err == out ? o : open(err.c_str(), mode, 0644);
  if (o < 0 || e < 0) _exit(126);
  dup2(o, 1);
  dup2(e, 2);
  if (const int null_fd = open("/dev/null", O_RDONLY); null_fd >= 0) dup2(null_fd, 0);
  if (!cwd.empty() && chdir(cwd.c_str()) != 0) {
    std::fprintf(stderr, "chdir %s: %s\n", cwd.c_str(), std::strerror(errno));
    _exit(126);
  }
  execvp(args[0], args.data());
  std::fprintf(stderr, "exec %s: %s\n", args[0], std::strerror(errno));
  _exit(127);
}

// A waitpid status as a shell shows it: the exit status, 128 + signal if killed, else -1.
inline int exitStatus(int status) {
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  if (WIFSIGNALED(status)) return 128 + WTERMSIG(status);
  return -1;
}

// Non-blocking: the exit status if the child has ended (then it is reaped), else nullopt.
inline std::optional<int> pollExit(pid_t pid) {
  int status = 0;
  const pid_t r = waitpid(pid, &status, WNOHANG);
  if (r == pid) return exitStatus(status);
  if (r < 0) return -1;
  return std::nullopt;
}

// Blocking: the exit status.
inline int waitExit(pid_t pid) {
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) return -1;
  }
  return exitStatus(status);
}

// Waits up to timeout_s for pid; its exit status, or -1 after killing it when it did not end in time.
inline int reap(pid_t pid, double timeout_s) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (true) {
    if (const std::optional<int> st = pollExit(pid)) return *st;
    if (std::chrono::steady_clock::now() > end) {
      kill(pid, SIGKILL);
      waitExit(pid);
      return -1;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
}

// A command-line program run to its end: its exit status (reap()'s) and what it wrote.
struct ToolRun {
  int status = -1;
  std::string out, err;
};
// Runs argv with stdout and stderr in `dir`'s out.txt and err.txt (overwritten), for at most
// timeout_s, and reads them back.
inline ToolRun runTool(const std::vector<std::string>& argv, const std::filesystem::path& dir, double timeout_s) {
  const std::string out = (dir / "out.txt").string(), err = (dir / "err.txt").string();
  ToolRun r;
  r.status = reap(spawnIn("", argv, out, err), timeout_s);
  r.out = slurp(out);
  r.err = slurp(err);
  return r;
}

// Polls `done` every 20 ms for up to timeout_s; its last answer.
inline bool waitUntil(const std::function<bool()>& done, double timeout_s) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (!done()) {
    if (std::chrono::steady_clock::now() > end) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return true;
}

// `sh -c command`: its exit status (-1 if it did not exit normally).
inline int shellStatus(const std::string& command) {
  const int raw = std::system(command.c_str());
  return WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
}

// argv as one line for a report (arguments with spaces quoted).
inline std::string commandLine(const std::vector<std::string>& argv) {
  std::string s;
  for (const std::string& a : argv) {
    if (!s.empty()) s += ' ';
    s += a.find(' ') == std::string::npos ? a : "'" + a + "'";
  }
  return s;
}

}  // namespace thx::test
