// hapticd and probe-client as separate processes over LCM udpm (ttl=0, a port of this test's own):
// a refusal at the client limit, rates capped by --max-rate, and batched CONTACT streams that
// deliver every tick (the bandwidth refusal is covered by test_subscriptions). Counts are checked with wide margins (no timing assertions: the
// sanitizer build runs slowly); the measured rates are in docs/clients.md. Skipped when udpm is
// not available (no multicast route).
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <lcm/lcm-cpp.hpp>
#include <regex>
#include <sstream>

namespace fs = std::filesystem;

namespace {

std::string slurp(const fs::path& p) {
  std::ifstream f(p);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

// "key": value in the probe's flat JSON (strings without quotes).
std::string jsonField(const std::string& json, const std::string& key) {
  const std::regex text("\"" + key + "\": \"([^\"]*)\"");
  const std::regex number("\"" + key + "\": ([^,\n]*)");
  std::smatch m;
  if (std::regex_search(json, m, text) || std::regex_search(json, m, number)) return m[1].str();
  return "<missing " + key + ">";
}
double jsonNumber(const std::string& json, const std::string& key) {
  try {
    return std::stod(jsonField(json, key));
  } catch (...) {
    return -1e300;
  }
}

int shell(const std::string& cmd) {
  const int raw = std::system(cmd.c_str());
  return WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
}

class ProbeLoopback : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("thx_probe_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    url_ = "udpm://239.255.76.67:" + std::to_string(20000 + ::getpid() % 10000) + "?ttl=0";
  }
  void TearDown() override {
    if (server_ > 0) {
      kill(server_, SIGKILL);
      waitpid(server_, nullptr, 0);
    }
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  std::string probe(const std::string& args, const std::string& name) const {
    return std::string("'") + THX_PROBE + "' --lcm-url '" + url_ + "' --client-id " + name + " --json '" +
           path(name + ".json") + "' --connect-timeout 30 --quiet " + args + " 2>'" + path(name + ".err") + "'";
  }
  void startServer(const std::string& args) {
    const std::string cmd = std::string("cd '") + THX_SOURCE_DIR + "' && exec '" + THX_HAPTICD +
                            "' --scene scenes/default.yaml --duration 0 --no-mlock --lcm-url '" + url_ + "' " + args +
                            " --stats-json '" + path("s.json") + "' --flight-dir '" + path("") + "' >'" +
                            path("hd.out") + "' 2>'" + path("hd.err") + "'";
    server_ = fork();
    ASSERT_GE(server_, 0);
    if (server_ == 0) {
      execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
      _exit(127);
    }
  }
  int stopServer() {
    kill(server_, SIGTERM);
    int status = 0;
    waitpid(server_, &status, 0);
    server_ = -1;
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }

  fs::path dir_;
  std::string url_;
  pid_t server_ = -1;
};

}  // namespace

TEST_F(ProbeLoopback, LimitsRatesAndBatchesEndToEnd) {
  {
    lcm::LCM check(url_);
    if (!check.good()) GTEST_SKIP() << "LCM udpm is not available here (" << url_ << "): no multicast route";
  }
  // Four probes at once against three client places: one is refused (whichever asks last).
  startServer("--max-clients 3 --max-rate 40");
  const char* names[] = {"state", "audio1", "audio2", "audio3"};
  std::string cmd = "(" + probe("--stream DEVICE_STATE --rate 100 --duration 1", "state") + ")";
  for (int k = 1; k < 4; ++k) cmd += " & (" + probe("--stream CONTACT --batch --rate 50 --duration 1", names[k]) + ")";
  cmd += " & wait";
  shell(cmd);

  int refused = 0;
  for (const char* name : names) {
    const std::string json = slurp(path(std::string(name) + ".json"));
    SCOPED_TRACE(std::string(name) + ": " + json + slurp(path(std::string(name) + ".err")));
    if (jsonField(json, "state") == "refused") {
      ++refused;
      EXPECT_NE(jsonField(json, "reason").find("too many clients: 3 connected, the limit is 3"), std::string::npos);
      EXPECT_EQ(jsonNumber(json, "messages"), 0);
      continue;
    }
    EXPECT_EQ(jsonField(json, "state"), "active");
    EXPECT_EQ(jsonField(json, "error"), "");
    EXPECT_EQ(jsonNumber(json, "granted_rate_hz"), 40.0);  // capped by --max-rate, with the reason
    EXPECT_NE(jsonField(json, "reason").find("--max-rate"), std::string::npos);
    EXPECT_EQ(jsonNumber(json, "duplicates"), 0);
    EXPECT_GE(jsonNumber(json, "messages"), 20);  // ~41 in 1 s; wide margin for the sanitizer build
    EXPECT_LE(jsonNumber(json, "messages"), 42);  // never above the granted rate
    if (std::string(name) == "state") {
      EXPECT_EQ(jsonField(json, "channel"), "THX_DEVICE_STATE.state");
    } else {
      EXPECT_EQ(jsonField(json, "channel"), std::string("THX_CONTACT_BATCH.") + name);
      EXPECT_GE(jsonNumber(json, "samples"), 500);  // ~1000 per second of servo ticks
      EXPECT_EQ(jsonNumber(json, "samples_missing"), 0);
      EXPECT_EQ(jsonNumber(json, "samples_out_of_order"), 0);
    }
  }
  EXPECT_EQ(refused, 1);

  EXPECT_EQ(stopServer(), 0) << slurp(path("hd.err"));
  const std::string log = slurp(path("hd.err"));
  EXPECT_NE(log.find("refused a subscription of client"), std::string::npos) << log;
  EXPECT_NE(log.find("(hapticd --max-clients)"), std::string::npos) << log;
}

TEST(ProbeClientCli, HelpAndBadCommandLines) {
  const std::string p = std::string("'") + THX_PROBE + "' ";
  EXPECT_EQ(shell(p + "--help >/dev/null"), 0);
  EXPECT_EQ(shell(p + "--stream DEVICE_STATE --rate 10 --duration 1 2>/dev/null"), 2);           // no --json
  EXPECT_EQ(shell(p + "--stream FORCES --rate 10 --duration 1 --json x 2>/dev/null"), 2);        // unknown stream
  EXPECT_EQ(shell(p + "--stream DEVICE_STATE --batch --rate 10 --duration 1 --json x 2>/dev/null"), 2);
  EXPECT_EQ(shell(p + "--stream CONTACT --rate -1 --duration 1 --json x 2>/dev/null"), 2);
  EXPECT_EQ(shell(p + "--stream CONTACT --rate 10 --duration 1 --json x --client-id 'a b' 2>/dev/null"), 2);
}
