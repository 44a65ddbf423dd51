// Load (issue 5): 16 clients against a real-time hapticd, as processes over LCM udpm (ttl=0, a
// port of this test's own): 4 at 1 kHz with batched CONTACT samples (every tick), 12 at 60 Hz
// DEVICE_STATE, for 5 s. Every client gets its rate within 1 % and at least 99.9 % of its
// messages (and of the samples); the servo keeps time with its force safe. The 60 s version,
// with the servo's compute p99 against a run without clients, is benchmarks/bench_clients.cpp.
// Skipped when udpm is not available (no multicast route).
#include <string>
#include <vector>

#include "hapticd_harness.hpp"

using namespace thx::test;

class HapticdLoad : public HapticdProcessTest {};

TEST_F(HapticdLoad, SixteenClientsEachGetTheirRateAndTheirMessages) {
  if (!udpmAvailable()) GTEST_SKIP() << "LCM udpm is not available here (" << url_ << "): no multicast route";
  constexpr double kSeconds = 5.0;
  startServer({"--quiet"});
  struct Client {
    std::string name;
    double rate;
    bool batch;
    pid_t pid;
  };
  std::vector<Client> clients;
  for (int k = 0; k < 16; ++k) {
    const bool audio = k < 4;
    Client c{(audio ? "audio" : "visual") + std::to_string(k), audio ? 1000.0 : 60.0, audio, -1};
    std::vector<std::string> args = {"--stream",   audio ? "CONTACT" : "DEVICE_STATE", "--rate", audio ? "1000" : "60",
                                     "--duration", std::to_string(kSeconds)};
    if (audio) args.push_back("--batch");
    c.pid = startProbe(c.name, args);
    clients.push_back(c);
  }
  for (const Client& c : clients) EXPECT_EQ(finishProbe(c.pid, 90), 0) << c.name << ": " << slurp(path(c.name + ".err"));
  for (const Client& c : clients) {
    const std::string j = probeJson(c.name);
    SCOPED_TRACE(c.name + ": " + j);
    EXPECT_EQ(jsonField(j, "state"), "active");
    EXPECT_EQ(jsonNumber(j, "granted_rate_hz"), c.rate);
    EXPECT_LT(std::abs(jsonNumber(j, "rate_error")), 0.01);  // achieved within 1 % of the rate
    const double messages = jsonNumber(j, "messages"), missing = jsonNumber(j, "missing");
    EXPECT_GE(messages, 0.99 * c.rate * kSeconds);
    EXPECT_GE(messages / (messages + missing), 0.999);  // >= 99.9 % of its messages
    EXPECT_EQ(jsonNumber(j, "duplicates"), 0);
    EXPECT_EQ(jsonNumber(j, "reconnects"), 0);
    if (c.batch) {
      const double samples = jsonNumber(j, "samples"), lost = jsonNumber(j, "samples_missing");
      EXPECT_GE(samples / (samples + lost), 0.999);  // every tick's contact sample
      EXPECT_EQ(jsonNumber(j, "samples_out_of_order"), 0);
      EXPECT_NEAR(jsonNumber(j, "sample_rate_hz"), 1000.0, 10.0);
    }
  }
  EXPECT_EQ(stopServer(), 0) << serverLog();
  expectServoKeptTime(kSeconds);
}
