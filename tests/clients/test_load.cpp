// Load (issue 5): clients against a real-time hapticd, as processes over LCM udpm (ttl=0, a port
// of this test's own). 16 clients: 4 at 1 kHz with batched CONTACT samples (every tick), 12 at
// 60 Hz DEVICE_STATE; and three DEVICE_STATE probes at 1000, 250 and 60 Hz. Each client is
// admitted at the rate it asked for and its stream flows as the protocol says (messages arrive,
// none twice, a batch's samples in order, on the channel the reply named); the servo runs with
// its force safe. How many messages arrive and how close each client comes to its rate depend on
// the scheduler (a client starved for 40 ms overflows its kernel buffer), so those are measured
// by benchmarks/bench_clients.cpp (docs/clients.md), never asserted here; the exact per-tick
// accounting of decimation and batches is tests/clients/test_subscriptions.cpp, in lock-step.
// Skipped when udpm is not available (no multicast route).
#include <string>
#include <vector>

#include "tests/support/hapticd_harness.hpp"

namespace test_load {

namespace {

using namespace thx::test;

struct Client {
  std::string name;
  std::string stream;
  double rate;
  bool batch;
  pid_t pid = -1;
};

class HapticdLoad : public HapticdProcessTest {
 protected:
  // Runs `clients` together against one real-time hapticd for `seconds`, then checks each.
  void runAndCheck(std::vector<Client> clients, double seconds) {
    startServer({"--quiet"});
    for (Client& c : clients) {
      std::vector<std::string> args = {"--stream", c.stream, "--rate", std::to_string(c.rate), "--duration",
                                       std::to_string(seconds)};
      if (c.batch) args.push_back("--batch");
      c.pid = startProbe(c.name, args);
    }
    for (const Client& c : clients)
      EXPECT_EQ(finishProbe(c.pid, 90), 0) << c.name << ": " << slurp(path(c.name + ".err"));
    EXPECT_EQ(stopServer(), 0) << serverLog();
    expectServoRanSafely();
    for (const Client& c : clients) {
      const std::string j = probeJson(c.name);
      SCOPED_TRACE(c.name);
      expectStreamFlowed(j);
      EXPECT_EQ(jsonNumber(j, "granted_rate_hz"), c.rate);
      EXPECT_EQ(jsonField(j, "channel"),
                std::string(c.batch ? "THX_CONTACT_BATCH." : "THX_" + c.stream + ".") + c.name);
    }
  }
};

}  // namespace

TEST_F(HapticdLoad, SixteenClientsAreAllAdmittedAndServed) {
  if (!udpmAvailable()) GTEST_SKIP() << "LCM udpm is not available here (" << url_ << "): no multicast route";
  std::vector<Client> clients;
  for (int k = 0; k < 4; ++k) clients.push_back({"audio" + std::to_string(k), "CONTACT", 1000.0, true});
  for (int k = 4; k < 16; ++k) clients.push_back({"visual" + std::to_string(k), "DEVICE_STATE", 60.0, false});
  runAndCheck(clients, 5.0);
}

// Issue 5's "done when": probe-clients at 1000, 250 and 60 Hz, run together.
TEST_F(HapticdLoad, ProbesAt1000And250And60HzAreGrantedTheirRatesTogether) {
  if (!udpmAvailable()) GTEST_SKIP() << "LCM udpm is not available here (" << url_ << "): no multicast route";
  runAndCheck({{"p1000", "DEVICE_STATE", 1000.0, false},
               {"p250", "DEVICE_STATE", 250.0, false},
               {"p60", "DEVICE_STATE", 60.0, false}},
              3.0);
}

}  // namespace test_load
