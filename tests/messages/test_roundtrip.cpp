// Encode/decode round trip of every thx_msgs type with non-trivial values, and the encoded
// sizes quoted in docs/messages.md.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "message_fixtures.hpp"

namespace test_roundtrip {

using namespace thx_test;

namespace {

template <class T>
T round_trip(const T& in) {
  const std::vector<std::uint8_t> buf = encode(in);
  T out{};
  const int n = out.decode(buf.data(), 0, int(buf.size()));
  EXPECT_EQ(n, int(buf.size())) << T::getTypeName();
  // The safe path gives the same result.
  T out2{};
  EXPECT_EQ(thx_msgs::try_decode(buf.data(), buf.size(), out2), int(buf.size()));
  expect_eq(out, out2);
  return out;
}

template <class T>
void check_round_trip(const T& in) {
  SCOPED_TRACE(T::getTypeName());
  const T out = round_trip(in);
  expect_eq(in, out);
  // Re-encoding the decoded message gives the same bytes.
  EXPECT_EQ(encode(in), encode(out));
}

}  // namespace

TEST(MessagesRoundTrip, DeviceState) {
  for (int k = 0; k < 3; ++k) check_round_trip(make_device_state(k));
}
TEST(MessagesRoundTrip, Contact) {
  for (int k = 0; k < 3; ++k) check_round_trip(make_contact(k));
}
TEST(MessagesRoundTrip, ContactBatch) {
  for (int n : {0, 1, 7, 1000}) {
    SCOPED_TRACE(n);
    check_round_trip(make_contact_batch(n, n));
  }
}
TEST(MessagesRoundTrip, ServoStats) {
  for (int k = 0; k < 3; ++k) check_round_trip(make_servo_stats(k));
}
TEST(MessagesRoundTrip, SubscribeRequest) {
  for (int k = 0; k < 3; ++k) check_round_trip(make_subscribe_request(k));
}
TEST(MessagesRoundTrip, SubscribeReply) {
  for (int k = 0; k < 3; ++k) check_round_trip(make_subscribe_reply(k));
  thx_msgs::subscribe_reply_t refused = make_subscribe_reply(1);
  refused.accepted = 0;
  refused.reason = "unknown stream \"FOO\"";
  refused.channel.clear();
  refused.rate_hz = 0;
  check_round_trip(refused);
}
TEST(MessagesRoundTrip, Heartbeat) {
  for (int k = 0; k < 3; ++k) check_round_trip(make_heartbeat(k));
}
TEST(MessagesRoundTrip, Hello) {
  for (int k = 0; k < 3; ++k) check_round_trip(make_hello(k));
}
TEST(MessagesRoundTrip, ClientForce) {
  for (int k = 0; k < 3; ++k) check_round_trip(make_client_force(k));
}

TEST(MessagesRoundTrip, ServerCommand) {
  for (int k = 0; k < 3; ++k) check_round_trip(make_server_command(k));
  for (int k = 0; k < 3; ++k) check_round_trip(make_server_command_reply(k));
}

// Edge values survive bit-exactly: extremes of the integer types, infinities, -0, denormals.
TEST(MessagesRoundTrip, ExtremeValues) {
  thx_msgs::device_state_t m = make_device_state(0);
  m.utime = std::numeric_limits<std::int64_t>::min();
  m.tick = std::numeric_limits<std::int64_t>::max();
  m.buttons = std::numeric_limits<std::int32_t>::min();
  m.p_world[0] = std::numeric_limits<double>::infinity();
  m.p_world[1] = -0.0;
  m.p_world[2] = std::numeric_limits<double>::denorm_min();
  m.v_world[0] = std::numeric_limits<double>::quiet_NaN();
  const std::vector<std::uint8_t> buf = encode(m);
  thx_msgs::device_state_t out{};
  ASSERT_EQ(out.decode(buf.data(), 0, int(buf.size())), int(buf.size()));
  EXPECT_EQ(out.utime, m.utime);
  EXPECT_EQ(out.tick, m.tick);
  EXPECT_EQ(out.buttons, m.buttons);
  EXPECT_EQ(out.p_world[0], m.p_world[0]);
  EXPECT_TRUE(std::signbit(out.p_world[1]));
  EXPECT_EQ(out.p_world[2], m.p_world[2]);
  EXPECT_TRUE(std::isnan(out.v_world[0]));  // NaN crosses the wire: receivers must check
}

// LCM 1.3.1 decodes doubles through an int64_t* cast (a strict-aliasing violation). Without
// -fno-strict-aliasing (carried by thx_messages), g++ -O2 returns the pre-decode value here.
namespace {
__attribute__((noinline)) double decoded_p_world_x(const std::vector<std::uint8_t>& buf) {
  thx_msgs::device_state_t m{};
  if (m.decode(buf.data(), 0, int(buf.size())) < 0) return -1.0;
  return m.p_world[0];
}
__attribute__((noinline)) double decoded_first_depth(const std::vector<std::uint8_t>& buf) {
  thx_msgs::contact_batch_t m{};
  if (m.decode(buf.data(), 0, int(buf.size())) < 0 || m.samples.empty()) return -1.0;
  return m.samples[0].depth;
}
}  // namespace

TEST(MessagesRoundTrip, DecodedDoublesAreNotStale) {
  thx_msgs::device_state_t m = make_device_state(0);
  m.p_world[0] = 3.5;
  EXPECT_EQ(decoded_p_world_x(encode(m)), 3.5);
  thx_msgs::contact_batch_t b = make_contact_batch(0, 1);
  b.samples[0].depth = 0.00125;
  EXPECT_EQ(decoded_first_depth(encode(b)), 0.00125);
}

// The numbers in docs/messages.md. A change here is a wire change: update the doc too.
TEST(MessagesEncodedSize, FixedSizeTypes) {
  EXPECT_EQ(thx_msgs::device_state_t{}.getEncodedSize(), 224);
  EXPECT_EQ(thx_msgs::contact_t{}.getEncodedSize(), 406);
  EXPECT_EQ(thx_msgs::servo_stats_t{}.getEncodedSize(), 196);
  EXPECT_EQ(thx_msgs::contact_sample_encoded_size(), 398);  // inside a batch: no fingerprint
}

TEST(MessagesEncodedSize, BatchIsHeaderPlusSamples) {
  for (int n : {0, 1, 2, 1000}) {
    const thx_msgs::contact_batch_t b = make_contact_batch(0, n);
    EXPECT_EQ(std::size_t(b.getEncodedSize()), thx_msgs::contact_batch_encoded_size(std::size_t(n)));
  }
  EXPECT_EQ(thx_msgs::kBatchHeaderBytes, 52u);
  // udpm sends channel + 1 + message in one datagram up to 65,499 bytes.
  const std::size_t longest_channel = thx_msgs::stream_channel("CONTACT", true, std::string(32, 'a')).size();
  for (std::size_t ch : {std::size_t(18 + 1), longest_channel, thx_msgs::kMaxChannelLength}) {
    const std::size_t n = thx_msgs::max_unfragmented_batch_samples(ch);
    EXPECT_EQ(n, 164u) << ch;
    EXPECT_LE(ch + 1 + thx_msgs::contact_batch_encoded_size(n), thx_msgs::kLcmShortMessageMaxSize);
    EXPECT_GT(ch + 1 + thx_msgs::contact_batch_encoded_size(n + 1), thx_msgs::kLcmShortMessageMaxSize);
  }
  EXPECT_EQ(thx_msgs::max_unfragmented_batch_samples(), 164u);
  EXPECT_EQ(thx_msgs::contact_batch_encoded_size(164), 65324u);
  EXPECT_EQ(thx_msgs::contact_batch_encoded_size(1000), 398052u);
}

// Types with strings: 8 (fingerprint) + fixed fields + (4 + length + 1) per string.
TEST(MessagesEncodedSize, StringTypes) {
  auto strings = [](std::initializer_list<const std::string*> s) {
    int n = 0;
    for (const std::string* p : s) n += 4 + int(p->size()) + 1;
    return n;
  };
  const auto req = make_subscribe_request(0);
  EXPECT_EQ(req.getEncodedSize(), 37 + strings({&req.client_id, &req.stream}));
  const auto rep = make_subscribe_reply(0);
  EXPECT_EQ(rep.getEncodedSize(), 54 + strings({&rep.client_id, &rep.stream, &rep.reason, &rep.channel, &rep.data_url}));
  const auto hb = make_heartbeat(0);
  EXPECT_EQ(hb.getEncodedSize(), 32 + strings({&hb.client_id}));
  const auto hello = make_hello(0);
  EXPECT_EQ(hello.getEncodedSize(),
            68 + strings({&hello.server_name, &hello.device, &hello.scene_name, &hello.control_url, &hello.device_names}));
  const auto cf = make_client_force(0);
  EXPECT_EQ(cf.getEncodedSize(), 116 + strings({&cf.client_id, &cf.source}));
  const auto cmd = make_server_command(0);
  EXPECT_EQ(cmd.getEncodedSize(), 28 + strings({&cmd.client_id, &cmd.argument}));
  const auto ack = make_server_command_reply(0);
  EXPECT_EQ(ack.getEncodedSize(), 45 + strings({&ack.client_id, &ack.reason}));
}

}  // namespace test_roundtrip
