// The example client of docs/clients.md §5 (clients/examples/minimal_client.cpp, target
// thx-minimal-client) as a user runs it: a process beside a real-time hapticd (udpm on the test's
// own port block; skipped without a multicast route). It must connect, name the server and its
// device, and end with both streams granted and something received on each. How many messages
// arrive depends on the scheduler, so no count is asserted beyond "some". And the quote in
// docs/clients.md §5 is the file's code, verbatim, so what the page shows is what compiles here.
#include <lcm/lcm-cpp.hpp>
#include <regex>
#include <string>

#include "tests/support/hapticd_harness.hpp"
#include "thx_msgs/protocol.hpp"

namespace test_minimal_client {

namespace {

using namespace thx::test;

// Counts the server's hellos (any that decode).
struct Hellos {
  void on(const lcm::ReceiveBuffer* rbuf, const std::string& /*channel*/) {
    thx_msgs::hello_t h;
    if (thx_msgs::try_decode(rbuf->data, rbuf->data_size, h) > 0) ++count;
  }
  int count = 0;
};

// The number in "NAME: active at RATE Hz, N messages" of the example's summary; -1 if no such line.
long long messagesOf(const std::string& out, const std::string& stream, const std::string& rate) {
  std::smatch m;
  if (!std::regex_search(out, m, std::regex(stream + ": active at " + rate + " Hz, ([0-9]+) messages"))) return -1;
  return std::stoll(m[1]);
}

class MinimalClient : public HapticdProcessTest {};

TEST_F(MinimalClient, ConnectsBesideHapticdAndReceivesItsStreams) {
  if (!udpmAvailable()) GTEST_SKIP() << "LCM udpm is not available here (" << url_ << "): no multicast route";
  // hapticd up and saying hello before the example starts: its connect timeout is a fixed 10 s,
  // and how long hapticd takes to load its scene on a busy machine is not what this checks.
  lcm::LCM lcm(url_);
  Hellos hellos;
  lcm.subscribe(thx_msgs::kChannelHello, &Hellos::on, &hellos);
  startServer({});
  ASSERT_TRUE(waitUntil([&] { return lcm.handleTimeout(100) >= 0 && hellos.count > 0; }, 60))
      << "no hello from hapticd within 60 s; it said:\n" << serverLog();

  const pid_t example = spawn({THX_MINIMAL_CLIENT, url_}, path("example.out"), path("example.err"));
  children_.push_back(example);
  const int rc = reap(example, 60);  // it runs 5 s on its own pacer, after the hello
  std::erase(children_, example);
  const std::string out = slurp(path("example.out"));
  SCOPED_TRACE("thx-minimal-client stdout:\n" + out + "\nstderr:\n" + slurp(path("example.err")));
  EXPECT_EQ(rc, 0);

  // Connected: the hello's server and device, and hapticd granted what it asked for.
  EXPECT_NE(out.find(", device "), std::string::npos);
  EXPECT_TRUE(serverLogHas("client minimal: DEVICE_STATE at 60 Hz on THX_DEVICE_STATE.minimal", 5)) << serverLog();
  EXPECT_TRUE(serverLogHas("client minimal: CONTACT (batched) at 100 Hz on THX_CONTACT_BATCH.minimal", 5))
      << serverLog();
  // Received: its loop printed a device state, and each stream counted messages.
  EXPECT_NE(out.find("tick "), std::string::npos);
  EXPECT_GT(messagesOf(out, "DEVICE_STATE", "60"), 0);
  EXPECT_GT(messagesOf(out, "CONTACT", "100"), 0);

  EXPECT_EQ(stopServer(), 0) << serverLog();
  expectServoRanSafely();
}

// docs/clients.md §5 quotes the example in its first ```cpp block: that block must be the source
// (a part of it, verbatim), so an edit to one without the other fails here.
TEST(MinimalClientQuote, DocsQuoteIsTheExampleSource) {
  const std::string source = slurp(std::string(THX_SOURCE_DIR) + "/clients/examples/minimal_client.cpp");
  const std::string doc = slurp(std::string(THX_SOURCE_DIR) + "/docs/clients.md");
  ASSERT_FALSE(source.empty());
  const std::size_t section = doc.find("\n## 5. A complete client");
  ASSERT_NE(section, std::string::npos) << "docs/clients.md has no section '## 5. A complete client'";
  const std::string fence = "```cpp\n";
  const std::size_t begin = doc.find(fence, section);
  ASSERT_NE(begin, std::string::npos);
  const std::size_t end = doc.find("\n```", begin + fence.size());
  ASSERT_NE(end, std::string::npos);
  const std::string quote = doc.substr(begin + fence.size(), end + 1 - begin - fence.size());
  EXPECT_GT(quote.size(), 200u);
  EXPECT_NE(source.find(quote), std::string::npos)
      << "docs/clients.md §5 quotes code that is not in clients/examples/minimal_client.cpp; the quote:\n"
      << quote;
}

}  // namespace

}  // namespace test_minimal_client
