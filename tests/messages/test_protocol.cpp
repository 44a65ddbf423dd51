// Conventions in thx_msgs/protocol.hpp: channel names, client ids, batch layout constants.
#include <gtest/gtest.h>

#include <lcm/lcm.h>

#include "message_fixtures.hpp"

namespace test_protocol {

using namespace thx_test;
using thx_msgs::stream_channel;

TEST(MessagesProtocol, StreamChannels) {
  EXPECT_EQ(stream_channel(thx_msgs::kStreamDeviceState, false, "visual"), "THX_DEVICE_STATE.visual");
  EXPECT_EQ(stream_channel(thx_msgs::kStreamContact, false, "physics"), "THX_CONTACT.physics");
  EXPECT_EQ(stream_channel(thx_msgs::kStreamContact, true, "audio"), "THX_CONTACT_BATCH.audio");
  EXPECT_EQ(stream_channel(thx_msgs::kStreamServoStats, false, "mon_1"), "THX_SERVO_STATS.mon_1");
  // Refusals: unknown stream, batching a stream without a batch type, bad client id.
  EXPECT_EQ(stream_channel("FOO", false, "audio"), "");
  EXPECT_EQ(stream_channel(thx_msgs::kStreamDeviceState, true, "audio"), "");
  EXPECT_EQ(stream_channel(thx_msgs::kStreamContact, false, "a.b"), "");
  EXPECT_EQ(stream_channel(thx_msgs::kStreamContact, false, ""), "");
}

// The typed streams: each name once, back and forth; what a user may type and what not.
TEST(MessagesProtocol, TypedStreams) {
  using thx_msgs::Stream;
  EXPECT_STREQ(thx_msgs::stream_name(Stream::DeviceState), "DEVICE_STATE");
  EXPECT_STREQ(thx_msgs::stream_name(Stream::Contact), "CONTACT");
  EXPECT_STREQ(thx_msgs::stream_name(Stream::ServoStats), "SERVO_STATS");
  EXPECT_STREQ(thx_msgs::stream_name(static_cast<Stream>(7)), "");
  for (Stream s : thx_msgs::kStreams) {
    EXPECT_EQ(thx_msgs::parse_stream(thx_msgs::stream_name(s)), s);
    EXPECT_TRUE(thx_msgs::is_known_stream(thx_msgs::stream_name(s)));
    EXPECT_NE(std::string(thx_msgs::kStreamNames).find(thx_msgs::stream_name(s)), std::string::npos);
    EXPECT_EQ(thx_msgs::stream_supports_batch(s), thx_msgs::stream_supports_batch(thx_msgs::stream_name(s)));
  }
  for (const char* bad : {"", "device_state", "CONTACT_BATCH", "FORCES", " CONTACT"}) {
    EXPECT_FALSE(thx_msgs::parse_stream(bad)) << bad;
  }
  EXPECT_EQ(stream_channel(Stream::Contact, true, "audio"), "THX_CONTACT_BATCH.audio");
  EXPECT_EQ(stream_channel(Stream::DeviceState, true, "audio"), "");
}

TEST(MessagesProtocol, LongestChannelFitsLcm) {
  const std::string id(thx_msgs::kMaxClientIdLength, 'x');
  ASSERT_TRUE(thx_msgs::is_valid_client_id(id));
  const std::string ch = stream_channel(thx_msgs::kStreamContact, true, id);
  EXPECT_LE(ch.size(), thx_msgs::kMaxChannelLength);
  EXPECT_EQ(thx_msgs::kMaxChannelLength, std::size_t(LCM_MAX_CHANNEL_NAME_LENGTH));
  for (const char* fixed : {thx_msgs::kChannelHello, thx_msgs::kChannelSubscribe, thx_msgs::kChannelSubscribeReply,
                            thx_msgs::kChannelHeartbeat, thx_msgs::kChannelClientForce}) {
    EXPECT_EQ(std::string(fixed).rfind("THX_", 0), 0u) << fixed;
  }
}

TEST(MessagesProtocol, ClientIdsAndTags) {
  for (const char* ok : {"a", "audio", "physics-2", "VIS_0", "0123456789abcdefghijABCDEFGHIJ_-"}) {
    EXPECT_TRUE(thx_msgs::is_valid_client_id(ok)) << ok;
  }
  for (const char* bad : {"", "a b", "a.b", "a/b", "ü", "a*", "(x)", "0123456789abcdefghijABCDEFGHIJ_-X"}) {
    EXPECT_FALSE(thx_msgs::is_valid_client_id(bad)) << bad;
  }
  EXPECT_FALSE(thx_msgs::is_valid_client_id(std::string_view("a\0b", 3)));
  EXPECT_TRUE(thx_msgs::is_valid_source_tag("physics.sphere3"));
  EXPECT_FALSE(thx_msgs::is_valid_source_tag(""));
  EXPECT_FALSE(thx_msgs::is_valid_source_tag("physics sphere"));
  EXPECT_FALSE(thx_msgs::is_valid_source_tag(std::string(33, 'a')));
}

TEST(MessagesProtocol, StreamNames) {
  EXPECT_TRUE(thx_msgs::is_known_stream("DEVICE_STATE"));
  EXPECT_TRUE(thx_msgs::is_known_stream("CONTACT"));
  EXPECT_TRUE(thx_msgs::is_known_stream("SERVO_STATS"));
  EXPECT_FALSE(thx_msgs::is_known_stream("CONTACT_BATCH"));  // batching is a flag, not a stream
  EXPECT_FALSE(thx_msgs::is_known_stream("contact"));
  EXPECT_TRUE(thx_msgs::stream_supports_batch("CONTACT"));
  EXPECT_FALSE(thx_msgs::stream_supports_batch("DEVICE_STATE"));
}

// kBatchCountOffset must match the generated encoder's field order.
TEST(MessagesProtocol, BatchCountOffsetMatchesEncoder) {
  thx_msgs::contact_batch_t b = make_contact_batch(0, 3);
  b.num_dropped = 0x0A0B0C0D;
  const std::vector<std::uint8_t> bytes = encode(b);
  const std::size_t o = thx_msgs::kBatchCountOffset;
  EXPECT_EQ(bytes[o - 4], 0x0A);
  EXPECT_EQ(bytes[o - 1], 0x0D);
  EXPECT_EQ(bytes[o + 0], 0);
  EXPECT_EQ(bytes[o + 3], 3);
  EXPECT_EQ(bytes.size(), thx_msgs::kBatchHeaderBytes + 3 * std::size_t(thx_msgs::contact_sample_encoded_size()));
}

TEST(MessagesProtocol, BatchCountConsistency) {
  thx_msgs::contact_batch_t b = make_contact_batch(0, 2);
  EXPECT_TRUE(thx_msgs::batch_count_consistent(b));
  b.samples.pop_back();
  EXPECT_FALSE(thx_msgs::batch_count_consistent(b));
  b.num_samples = -1;
  EXPECT_FALSE(thx_msgs::batch_count_consistent(b));
  EXPECT_TRUE(thx_msgs::batch_count_consistent(make_contact_batch(0, 0)));
}

TEST(MessagesProtocol, Constants) {
  EXPECT_EQ(thx_msgs::contact_t::MAX_PLANES, 4);
  EXPECT_EQ(thx_msgs::hello_t::PROTOCOL_VERSION, 6);
  // Flags are distinct single bits.
  using D = thx_msgs::device_state_t;
  const std::int32_t flags[] = {D::FLAG_ENGAGED,  D::FLAG_RAMPING,       D::FLAG_SAFETY_CLAMP,
                                D::FLAG_IN_CONTACT, D::FLAG_MISSED_TICK, D::FLAG_CLIENT_FORCE,
                                D::FLAG_SIMULATED,  D::FLAG_FAULT,        D::FLAG_SCENE_SWITCHING,
                                D::FLAG_PROXY_HELD};
  std::int32_t all = 0;
  for (std::int32_t f : flags) {
    EXPECT_EQ(f & (f - 1), 0) << f;
    EXPECT_EQ(all & f, 0) << f;
    all |= f;
  }
}

}  // namespace test_protocol
