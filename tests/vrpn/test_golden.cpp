// Golden tests from the stock-program captures (docs/vrpn.md §11): every captured message decodes
// to the expected values, and encoding those values gives exactly the captured bytes. The one
// allowed difference: padding, which stock senders leave as garbage and we write as zeros.
#include <gtest/gtest.h>

#include <string>

#include "tests/vrpn/message_body.hpp"
#include "device/vrpn/base_messages.hpp"
#include "device/vrpn/button_messages.hpp"
#include "device/vrpn/cookie.hpp"
#include "device/vrpn/force_messages.hpp"
#include "device/vrpn/frame_decoder.hpp"
#include "device/vrpn/system_messages.hpp"
#include "device/vrpn/tracker_messages.hpp"
#include "tests/vrpn/transcripts.hpp"

namespace test_golden {

using namespace thx::vrpn;
using thx::vrpn::transcript::hex;
namespace tx = thx::vrpn::transcript;

namespace {

using Bytes = std::vector<std::uint8_t>;

// The one message `bytes` holds; fails the test unless it is exactly one whole message.
struct Decoded {
  Header header;
  Bytes payload;
};
Decoded decodeOne(const Bytes& bytes) {
  FrameDecoder d;
  d.feed(bytes);
  DecodeStep step = d.next();
  EXPECT_TRUE(std::holds_alternative<Frame>(step));
  if (!std::holds_alternative<Frame>(step)) return {};
  const Frame& f = std::get<Frame>(step);
  Decoded out{f.header, Bytes(f.payload.begin(), f.payload.end())};
  EXPECT_TRUE(std::holds_alternative<NeedMore>(d.next()));
  EXPECT_EQ(d.buffered(), 0u);
  return out;
}

Bytes frame(const Header& h, const Bytes& payload) {
  Bytes out;
  EXPECT_TRUE(appendFrame(out, h, payload));
  return out;
}

using thx::vrpn::test::body;

Header header(std::uint32_t sec, std::uint32_t usec, std::int32_t sender, std::int32_t type, std::uint32_t seq,
              std::uint32_t payload_length) {
  return Header{payload_length, TimeValue{sec, usec}, sender, type, seq};
}

}  // namespace

TEST(Golden, Cookie) {
  const Bytes captured = hex(tx::kCookie);
  const Cookie ours = makeCookie(0);
  EXPECT_EQ(Bytes(ours.begin(), ours.end()), captured);
  Result<PeerCookie> peer = checkCookie(captured);
  ASSERT_TRUE(peer) << peer.error().reason;
  EXPECT_EQ(peer->version, "vrpn: ver. 07.38");
  EXPECT_EQ(peer->log_mode, 0);
  EXPECT_FALSE(peer->minor_differs);
}

TEST(Golden, SenderDescriptionVrpnControl) {
  const Bytes captured = hex(tx::kSenderVrpnControl);
  const Decoded d = decodeOne(captured);
  EXPECT_EQ(d.header, header(0x6b022912, 0x000b5c86, 0, kSenderDescription, 1, 17));
  Result<std::string_view> name = decodeDescription(d.payload);
  ASSERT_TRUE(name) << name.error().reason;
  EXPECT_EQ(*name, "VRPN Control");

  Bytes b;
  encodeDescription("VRPN Control", b);
  EXPECT_EQ(frame(d.header, b), captured);
}

TEST(Golden, SenderDescriptionTracker0Body) {
  const Bytes captured = hex(tx::kSenderTracker0Body);
  Result<std::string_view> name = decodeDescription(captured);
  ASSERT_TRUE(name) << name.error().reason;
  EXPECT_EQ(*name, "Tracker0");
  Bytes b;
  encodeDescription("Tracker0", b);
  EXPECT_EQ(b, captured);
}

TEST(Golden, TypeDescriptionPosQuat) {
  const Bytes captured = hex(tx::kTypePosQuat);
  const Decoded d = decodeOne(captured);
  EXPECT_EQ(d.header, header(0x6b022912, 0x000b5c88, 4, kTypeDescription, 10, 26));
  Result<std::string_view> name = decodeDescription(d.payload);
  ASSERT_TRUE(name) << name.error().reason;
  EXPECT_EQ(*name, TrackerPosQuat::kTypeName);

  Bytes b;
  encodeDescription(TrackerPosQuat::kTypeName, b);
  EXPECT_EQ(frame(d.header, b), captured);
}

TEST(Golden, UdpDescriptionFraming) {
  const Bytes captured = hex(tx::kUdpDescription);
  const Decoded d = decodeOne(captured);
  EXPECT_EQ(d.header, header(0x6b022912, 0x000b5c83, 52198, kUdpDescription, 0, 10));
  const std::string ip(d.payload.begin(), d.payload.end());
  EXPECT_EQ(ip, std::string("127.0.0.1\0", 10));
  EXPECT_EQ(frame(d.header, d.payload), captured);
}

TEST(Golden, TrackerPosQuat) {
  const Bytes captured = hex(tx::kPosQuat);
  const Decoded d = decodeOne(captured);
  EXPECT_EQ(d.header, header(0x6b022912, 0x000bcea6, 1, 4, 3, 64));
  Result<TrackerPosQuat> m = TrackerPosQuat::decode(d.payload);
  ASSERT_TRUE(m) << m.error().reason;
  TrackerPosQuat expected;
  expected.sensor = 0;
  expected.pos = {0.0, 0.0, 0.0};
  expected.quat = {0.0, tx::kPosQuatY, 0.0, tx::kPosQuatW};
  EXPECT_EQ(*m, expected);
  EXPECT_NEAR(m->quat[1], 0.8925, 1e-4);
  EXPECT_NEAR(m->quat[3], 0.4510, 1e-4);

  EXPECT_EQ(frame(d.header, body(expected)), captured);
}

TEST(Golden, ButtonStatesPaddingIgnoredOnInputZeroOnOutput) {
  const Bytes captured = hex(tx::kButtonStates);
  ASSERT_EQ(captured.size(), 40u);
  const Decoded d = decodeOne(captured);
  EXPECT_EQ(d.header, header(0x6b022933, 0x0004a847, 2, 19, 31, 12));
  Result<ButtonStates> m = ButtonStates::decode(d.payload);
  ASSERT_TRUE(m) << m.error().reason;
  EXPECT_EQ(m->states, (std::vector<std::int32_t>{1, 1}));

  // Byte-exact over the 36 counted bytes; our padding is zeros where the capture has "trol".
  Bytes expected = captured;
  std::fill(expected.begin() + 36, expected.end(), std::uint8_t{0});
  EXPECT_EQ(frame(d.header, body(ButtonStates{{1, 1}})), expected);
}

TEST(Golden, PingAndPong) {
  const Bytes ping = hex(tx::kPing);
  const Decoded dp = decodeOne(ping);
  EXPECT_EQ(dp.header, header(0x6b022934, 0x000c8551, 1, 16, 31, 0));
  EXPECT_TRUE(Ping::decode(dp.payload));
  EXPECT_EQ(frame(dp.header, body(Ping{})), ping);

  const Bytes pong = hex(tx::kPong);
  const Decoded dq = decodeOne(pong);
  EXPECT_EQ(dq.header, header(0x6b022934, 0x000c898e, 1, 17, 101, 0));
  EXPECT_TRUE(Pong::decode(dq.payload));
  EXPECT_EQ(frame(dq.header, body(Pong{})), pong);
}

TEST(Golden, ForcePlaneFromSphereClient) {
  const Bytes captured = hex(tx::kPlane);
  const Decoded d = decodeOne(captured);
  EXPECT_EQ(d.header, header(0x6b02293b, 0x000cd7b7, 1, 6, 58, 40));
  Result<ForcePlane> m = ForcePlane::decode(d.payload);
  ASSERT_TRUE(m) << m.error().reason;
  ForcePlane expected;
  expected.plane = {0.0f, 1.0f, 0.0f, 100.0f};
  expected.kspring = 1.0f;
  expected.kdamp = 0.0f;
  expected.fdyn = 0.05f;
  expected.fstat = 0.1f;
  expected.plane_index = 0;
  expected.n_rec_cycles = 10;
  EXPECT_EQ(*m, expected);

  EXPECT_EQ(frame(d.header, body(expected)), captured);
}

}  // namespace test_golden
