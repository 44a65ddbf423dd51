// The LCM messages hapticd takes from the network under the short fixed-seed fuzz run
// (tests/fuzz/short_run.hpp, body in lcm_messages_body.hpp), its seeds, and the regressions the
// fuzzing found.
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>

#include "tests/fuzz/lcm_messages_body.hpp"
#include "tests/fuzz/seed_writer.hpp"
#include "tests/fuzz/short_run.hpp"
#include "tests/messages/message_fixtures.hpp"

namespace thx::fuzz::test_fuzz_lcm_messages {
namespace {

using namespace thx_msgs;

template <class T>
Bytes seed(std::uint8_t channel, const T& m) {
  Bytes b{channel};
  const Bytes e = lcm_messages::encoded(m);
  b.insert(b.end(), e.begin(), e.end());
  return b;
}

// A message of each kind hapticd accepts, on its channel, and every other type's fixture.
std::vector<std::pair<std::string, Bytes>> seeds() {
  subscribe_request_t sub{};
  sub.utime = 1;
  sub.seq = 2;
  sub.client_id = "audio";
  sub.stream = "CONTACT";
  sub.action = subscribe_request_t::ACTION_SUBSCRIBE;
  sub.rate_hz = 100.0;
  sub.batch = 1;
  heartbeat_t hb{};
  hb.seq = 3;
  hb.client_id = "fuzz";
  server_command_t reset{};
  reset.client_id = "ctl";
  reset.action = server_command_t::ACTION_RESET_FAULTS;
  server_command_t load = reset;
  load.action = server_command_t::ACTION_LOAD_SCENE;
  load.argument = "default";
  client_force_t force{};
  force.seq = 1;
  force.client_id = "physics";
  force.source = "ball0";
  force.timeout_us = 50000;
  force.f_world[0] = 0.1;
  force.f_world[1] = 0.2;
  force.f_world[2] = -0.3;
  return {{"subscribe", seed(0, sub)},
          {"heartbeat", seed(1, hb)},
          {"command_reset", seed(2, reset)},
          {"command_load", seed(2, load)},
          {"client_force", seed(3, force)},
          {"device_state", seed(0, thx_test::make_device_state(1))},
          {"contact_batch", seed(1, thx_test::make_contact_batch(1, 2))},
          {"hello", seed(2, thx_test::make_hello(1))},
          {"subscribe_reply", seed(3, thx_test::make_subscribe_reply(1))},
          {"command_reply", seed(0, thx_test::make_server_command_reply(1))}};
}

TEST(FuzzLcmMessages, WriteSeedCorpusWhenAsked) { writeSeedsWhenAsked(seeds()); }

TEST(FuzzLcmMessages, CheckedInSeedsAreTheGeneratedOnes) {
  // Guards the corpus's value: each of hapticd's four kinds is there and passes its checks.
  const std::vector<Bytes> corpus = loadCorpus("lcm_messages");
  for (const auto& [name, bytes] : seeds()) {
    EXPECT_NE(std::find(corpus.begin(), corpus.end(), bytes), corpus.end()) << name << " missing from the corpus";
  }
}

TEST(FuzzLcmMessages, AcceptedSeedsReachTheChecks) {
  const auto all = seeds();
  for (std::size_t i = 0; i < 5; ++i) {
    const Bytes& b = all[i].second;
    subscribe_request_t r;
    heartbeat_t h;
    server_command_t c;
    client_force_t f;
    const void* p = b.data() + 1;
    const std::size_t n = b.size() - 1;
    const std::string problem = b[0] == 0   ? srv::decodeUntrusted(p, n, r)
                                : b[0] == 1 ? srv::decodeUntrusted(p, n, h)
                                : b[0] == 2 ? srv::decodeUntrusted(p, n, c)
                                            : srv::decodeUntrusted(p, n, f);
    EXPECT_EQ(problem, "") << all[i].first;
  }
}

// Found by the short run (corpus/lcm_messages/regression_embedded_nul, a subscribe_reply_t whose
// reason held NULs): try_decode accepted a string with a NUL before its end, which the encoder
// then cut, so the message changed on a round trip. Now refused, on every channel.
TEST(FuzzLcmMessages, AStringWithAnEmbeddedNulIsRefused) {
  heartbeat_t hb{};
  hb.client_id = "abc";
  Bytes b = lcm_messages::encoded(hb);
  heartbeat_t out;
  ASSERT_EQ(try_decode(b.data(), b.size(), out), int(b.size()));
  b[b.size() - 3] = 0;  // "a\0c"
  EXPECT_EQ(try_decode(b.data(), b.size(), out), -1);
  EXPECT_EQ(srv::decodeUntrusted(b.data(), b.size(), out),
            "malformed heartbeat_t (" + std::to_string(b.size()) +
                " bytes): truncated, or a string length or count outside the message");
  std::ifstream f(std::string(THX_SOURCE_DIR) + "/tests/fuzz/corpus/lcm_messages/regression_embedded_nul", std::ios::binary);
  const Bytes found((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  ASSERT_GT(found.size(), 1u);
  subscribe_reply_t reply;
  EXPECT_EQ(try_decode(found.data() + 1, found.size() - 1, reply), -1);
}

TEST(FuzzLcmMessages, ShortRun) { shortRun("lcm_messages", &lcm_messages::fuzzOnce); }

}  // namespace
}  // namespace thx::fuzz::test_fuzz_lcm_messages
