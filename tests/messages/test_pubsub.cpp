// Publish/subscribe round trips through lcm::LCM("memq://"): in-process, no network, no root.
#include <gtest/gtest.h>

#include <lcm/lcm-cpp.hpp>

#include <optional>

#include "message_fixtures.hpp"

namespace test_pubsub {

using namespace thx_test;

namespace {

// Typed subscription: LCM decodes (fine for trusted, server-sent messages).
template <class T>
struct TypedSink {
  std::vector<T> got;
  std::vector<std::string> channels;
  void on(const lcm::ReceiveBuffer*, const std::string& channel, const T* msg) {
    got.push_back(*msg);
    channels.push_back(channel);
  }
};

// Untyped subscription + try_decode: the pattern for anything a peer may corrupt.
template <class T>
struct RawSink {
  std::vector<T> got;
  int failures = 0;
  void on(const lcm::ReceiveBuffer* rbuf, const std::string&) {
    T m{};
    if (thx_msgs::try_decode(rbuf->data, rbuf->data_size, m) > 0) {
      got.push_back(std::move(m));
    } else {
      ++failures;
    }
  }
};

// Handles everything queued; memq delivers synchronously on handle().
int drain(lcm::LCM& lcm) {
  int handled = 0;
  while (lcm.handleTimeout(0) > 0) ++handled;
  return handled;
}

template <class T>
void check_pubsub(const T& msg, const std::string& channel) {
  SCOPED_TRACE(T::getTypeName());
  lcm::LCM lcm("memq://");
  ASSERT_TRUE(lcm.good());
  TypedSink<T> typed;
  RawSink<T> raw;
  lcm.subscribe(channel, &TypedSink<T>::on, &typed);
  lcm.subscribe(channel, &RawSink<T>::on, &raw);
  ASSERT_EQ(lcm.publish(channel, &msg), 0);
  EXPECT_EQ(drain(lcm), 1);
  ASSERT_EQ(typed.got.size(), 1u);
  EXPECT_EQ(typed.channels[0], channel);
  expect_eq(msg, typed.got[0]);
  ASSERT_EQ(raw.got.size(), 1u);
  EXPECT_EQ(raw.failures, 0);
  expect_eq(msg, raw.got[0]);
}

}  // namespace

TEST(MessagesPubSub, EveryTypeOverMemq) {
  const std::string id = "client-1";
  check_pubsub(make_device_state(2), thx_msgs::stream_channel(thx_msgs::kStreamDeviceState, false, id));
  check_pubsub(make_contact(2), thx_msgs::stream_channel(thx_msgs::kStreamContact, false, id));
  check_pubsub(make_contact_batch(2, 5), thx_msgs::stream_channel(thx_msgs::kStreamContact, true, id));
  check_pubsub(make_servo_stats(2), thx_msgs::stream_channel(thx_msgs::kStreamServoStats, false, id));
  check_pubsub(make_subscribe_request(2), thx_msgs::kChannelSubscribe);
  check_pubsub(make_subscribe_reply(2), thx_msgs::kChannelSubscribeReply);
  check_pubsub(make_heartbeat(2), thx_msgs::kChannelHeartbeat);
  check_pubsub(make_hello(2), thx_msgs::kChannelHello);
  check_pubsub(make_client_force(2), thx_msgs::kChannelClientForce);
  check_pubsub(make_server_command(2), thx_msgs::kChannelCommand);
  check_pubsub(make_server_command_reply(2), thx_msgs::kChannelCommandReply);
}

TEST(MessagesPubSub, EmptyBatch) {
  check_pubsub(make_contact_batch(3, 0), thx_msgs::stream_channel(thx_msgs::kStreamContact, true, "audio"));
}

// 1000 samples = one second of ticks: 394 kB, larger than one UDP datagram (fine on memq;
// on udpm LCM would fragment it, see docs/messages.md).
TEST(MessagesPubSub, ThousandSampleBatch) {
  const thx_msgs::contact_batch_t batch = make_contact_batch(4, 1000);
  EXPECT_EQ(std::size_t(batch.getEncodedSize()), thx_msgs::contact_batch_encoded_size(1000));
  check_pubsub(batch, thx_msgs::stream_channel(thx_msgs::kStreamContact, true, "audio"));
}

// Sequence numbers let a receiver see lost batches; the order on one channel is preserved.
TEST(MessagesPubSub, BatchSequenceGapIsVisible) {
  lcm::LCM lcm("memq://");
  ASSERT_TRUE(lcm.good());
  RawSink<thx_msgs::contact_batch_t> sink;
  const std::string ch = thx_msgs::stream_channel(thx_msgs::kStreamContact, true, "audio");
  lcm.subscribe(ch, &RawSink<thx_msgs::contact_batch_t>::on, &sink);
  for (std::int64_t seq : {1, 2, 4}) {
    thx_msgs::contact_batch_t b = make_contact_batch(0, 2);
    b.seq = seq;
    ASSERT_EQ(lcm.publish(ch, &b), 0);
  }
  EXPECT_EQ(drain(lcm), 3);
  ASSERT_EQ(sink.got.size(), 3u);
  int gaps = 0;
  for (std::size_t i = 1; i < sink.got.size(); ++i) gaps += sink.got[i].seq != sink.got[i - 1].seq + 1;
  EXPECT_EQ(gaps, 1);
}

// LCM treats a subscription's channel as a regex anchored at both ends: per-client channels
// of "audio" and "audio2" do not cross.
TEST(MessagesPubSub, PerClientChannelsAreSeparate) {
  lcm::LCM lcm("memq://");
  ASSERT_TRUE(lcm.good());
  TypedSink<thx_msgs::device_state_t> a, a2;
  lcm.subscribe(thx_msgs::stream_channel(thx_msgs::kStreamDeviceState, false, "audio"),
                &TypedSink<thx_msgs::device_state_t>::on, &a);
  lcm.subscribe(thx_msgs::stream_channel(thx_msgs::kStreamDeviceState, false, "audio2"),
                &TypedSink<thx_msgs::device_state_t>::on, &a2);
  const thx_msgs::device_state_t m = make_device_state(0);
  lcm.publish(thx_msgs::stream_channel(thx_msgs::kStreamDeviceState, false, "audio2"), &m);
  lcm.publish(thx_msgs::stream_channel(thx_msgs::kStreamDeviceState, false, "audio2"), &m);
  lcm.publish(thx_msgs::stream_channel(thx_msgs::kStreamDeviceState, false, "audio"), &m);
  drain(lcm);
  EXPECT_EQ(a.got.size(), 1u);
  EXPECT_EQ(a2.got.size(), 2u);
}

// A message of the wrong type on a channel is dropped by the raw sink, not misread.
TEST(MessagesPubSub, WrongTypeOnChannelIsRejected) {
  lcm::LCM lcm("memq://");
  ASSERT_TRUE(lcm.good());
  RawSink<thx_msgs::client_force_t> sink;
  lcm.subscribe(thx_msgs::kChannelClientForce, &RawSink<thx_msgs::client_force_t>::on, &sink);
  const thx_msgs::heartbeat_t hb = make_heartbeat(0);
  lcm.publish(thx_msgs::kChannelClientForce, &hb);
  const std::uint8_t junk[3] = {1, 2, 3};
  lcm.publish(thx_msgs::kChannelClientForce, junk, sizeof junk);
  drain(lcm);
  EXPECT_TRUE(sink.got.empty());
  EXPECT_EQ(sink.failures, 2);
}

}  // namespace test_pubsub
