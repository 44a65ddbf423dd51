#pragma once
// hapticd and its clients as processes, for the load and fault tests (test_load.cpp,
// test_faults.cpp): start them with their output in a scratch directory, signal and reap them,
// read the JSON they write, and check that the servo kept time with its force safe.
// Needs THX_HAPTICD, THX_PROBE and THX_SOURCE_DIR (compile definitions).
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <lcm/lcm-cpp.hpp>
#include <regex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace thx::test {

namespace fs = std::filesystem;

inline std::string slurp(const fs::path& p) {
  std::ifstream f(p);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

// The value after "key": in a flat JSON text (hapticd's --stats-json, probe-client's --json);
// strings without their quotes. "<missing KEY>" when absent.
inline std::string jsonField(const std::string& json, const std::string& key) {
  const std::regex text("\"" + key + "\": \"([^\"]*)\"");
  const std::regex number("\"" + key + "\": ([^,}\n]*)");
  std::smatch m;
  if (std::regex_search(json, m, text) || std::regex_search(json, m, number)) return m[1].str();
  return "<missing " + key + ">";
}
inline double jsonNumber(const std::string& json, const std::string& key) {
  try {
    return std::stod(jsonField(json, key));
  } catch (...) {
    return NAN;
  }
}

// fork + exec argv (argv[0] a path) in `cwd`, with stdout and stderr to files.
inline pid_t spawn(const std::vector<std::string>& argv, const std::string& out, const std::string& err,
                   const std::string& cwd = THX_SOURCE_DIR) {
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  const pid_t pid = fork();
  if (pid != 0) return pid;
  if (chdir(cwd.c_str()) != 0) _exit(126);
  const int o = open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  const int e = open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (o < 0 || e < 0) _exit(126);
  dup2(o, 1);
  dup2(e, 2);
  execv(args[0], args.data());
  _exit(127);
}

// Waits up to timeout_s for pid; returns its exit status (128 + signal if killed), or -1 after
// killing it when it did not end in time.
inline int reap(pid_t pid, double timeout_s) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  int status = 0;
  while (waitpid(pid, &status, WNOHANG) == 0) {
    if (std::chrono::steady_clock::now() > end) {
      kill(pid, SIGKILL);
      waitpid(pid, &status, 0);
      return -1;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

inline bool waitUntil(const std::function<bool()>& done, double timeout_s) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (!done()) {
    if (std::chrono::steady_clock::now() > end) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return true;
}

// A scratch directory, a udpm URL on a port of this test's own (ttl=0: nothing leaves the host),
// hapticd as a child process, probe-clients.
class HapticdProcessTest : public ::testing::Test {
 protected:
  void SetUp() override {
    static int counter = 0;
    const int n = counter++;
    dir_ = fs::temp_directory_path() / ("thx_hd_" + std::to_string(::getpid()) + "_" + std::to_string(n));
    fs::create_directories(dir_);
    // recv_buf_size: every socket on the bus receives every stream (~4,700 datagrams/s in the load
    // test, 100 kB datagrams in the fault test); the kernel's default UDP buffer (rmem_default,
    // ~208 kB, ~40 ms of the load) overflows whenever a client is descheduled that long on two
    // busy cores. LCM asks for more only when the URL says so (capped by net.core.rmem_max).
    url_ = "udpm://239.255.76.67:" + std::to_string(30000 + (::getpid() % 2000) * 8 + n % 8) +
           "?ttl=0&recv_buf_size=4194304";
  }
  void TearDown() override {
    for (pid_t p : children_) {
      kill(p, SIGKILL);
      kill(p, SIGCONT);
      waitpid(p, nullptr, 0);
    }
    if (server_ > 0) {
      kill(server_, SIGKILL);
      waitpid(server_, nullptr, 0);
    }
    std::error_code ec;
    // Kept for a look when something failed, or when THX_KEEP_TEST_DIR is set.
    if (!HasFailure() && !std::getenv("THX_KEEP_TEST_DIR")) fs::remove_all(dir_, ec);
  }

  bool udpmAvailable() const {
    lcm::LCM check(url_);
    return check.good();
  }

  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  std::vector<std::string> hapticdArgs(const std::vector<std::string>& extra) const {
    std::vector<std::string> a = {THX_HAPTICD,  "--scene",      "scenes/default.yaml", "--no-mlock",
                                  "--lcm-url",  url_,           "--stats-json",        path("s.json"),
                                  "--flight-dir", path("")};
    a.insert(a.end(), extra.begin(), extra.end());
    return a;
  }
  // hapticd until stopServer() (--duration 0), unless `extra` says otherwise.
  void startServer(const std::vector<std::string>& extra) {
    std::vector<std::string> e = {"--duration", "0"};
    e.insert(e.end(), extra.begin(), extra.end());
    server_ = spawn(hapticdArgs(e), path("hd.out"), path("hd.err"));
    ASSERT_GT(server_, 0);
  }
  int stopServer() {
    kill(server_, SIGTERM);
    const int rc = reap(server_, 20);
    server_ = -1;
    return rc;
  }
  std::string serverLog() const { return slurp(path("hd.err")); }
  bool serverLogHas(const std::string& text, double timeout_s) const {
    return waitUntil([&] { return serverLog().find(text) != std::string::npos; }, timeout_s);
  }

  // probe-client NAME with its JSON at NAME.json, its stderr at NAME.err.
  pid_t startProbe(const std::string& name, const std::vector<std::string>& args) {
    std::vector<std::string> a = {THX_PROBE,   "--lcm-url", url_,     "--client-id", name, "--json",
                                  path(name + ".json"), "--connect-timeout", "30", "--quiet"};
    a.insert(a.end(), args.begin(), args.end());
    const pid_t p = spawn(a, path(name + ".out"), path(name + ".err"));
    children_.push_back(p);
    return p;
  }
  int finishProbe(pid_t p, double timeout_s) {
    const int rc = reap(p, timeout_s);
    std::erase(children_, p);
    return rc;
  }
  std::string probeJson(const std::string& name) const { return slurp(path(name + ".json")); }

  // The servo ran and its force stayed safe. What a client fault must not do is let an unsafe force
  // through or stop the servo; that no tick ever waits on a client is proven deterministically
  // (tests/server/test_servo_no_alloc.cpp: no allocation, lock or system call in the tick). How
  // punctually the servo ticks beside its clients on this shared 2-core VM (missed deadlines,
  // achieved rate, snapshots the publisher could not take) depends on the scheduler, so it is
  // measured by the benchmarks (bench_clients, bench_latency) and never asserted here (DESIGN
  // rule 7; CI has seen 2.3 % of deadlines missed to VM stalls with the sanitizer tree beside).
  void expectServoRanSafely() const {
    const std::string s = slurp(path("s.json"));
    SCOPED_TRACE("hapticd --stats-json: " + s);
    EXPECT_GT(jsonNumber(s, "ticks"), 0);
    EXPECT_EQ(jsonField(s, "mode"), "realtime");
    const double f = jsonNumber(s, "max_force_n");
    EXPECT_TRUE(std::isfinite(f));
    EXPECT_LE(f, 7.9 + 1e-9);  // the PHANToM Desktop's peak force: the safety stage's clamp
  }

  // A probe's stream flowed as the protocol says: granted, messages arrived, none twice, and a
  // batch's samples in tick order. How many arrived depends on the scheduler (a starved probe's
  // kernel buffer overflows), so delivery shares are bench_clients' table, not a test's assertion.
  void expectStreamFlowed(const std::string& probe_json) const {
    SCOPED_TRACE("probe: " + probe_json);
    EXPECT_EQ(jsonField(probe_json, "state"), "active");
    EXPECT_EQ(jsonField(probe_json, "error"), "");
    EXPECT_GT(jsonNumber(probe_json, "messages"), 0);
    EXPECT_EQ(jsonNumber(probe_json, "duplicates"), 0);
    if (jsonField(probe_json, "batch") == "true") {
      EXPECT_GT(jsonNumber(probe_json, "samples"), 0);
      EXPECT_EQ(jsonNumber(probe_json, "samples_out_of_order"), 0);
    }
  }

  fs::path dir_;
  std::string url_;
  pid_t server_ = -1;
  std::vector<pid_t> children_;
};

}  // namespace thx::test
