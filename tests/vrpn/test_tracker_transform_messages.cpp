// The tracker transform requests and replies a stock vrpn_Phantom answers (docs/vrpn.md §7, §9):
// golden-style byte tests written from the §7 layouts (no capture of these exists): exact type
// names, exact body bytes both ways, whole frames, and the exact-size rule.
#include <gtest/gtest.h>

#include "tests/vrpn/message_body.hpp"
#include "device/vrpn/frame.hpp"
#include "device/vrpn/frame_decoder.hpp"
#include "device/vrpn/tracker_transform_messages.hpp"
#include "tests/vrpn/transcripts.hpp"

namespace test_tracker_transform_messages {

using namespace thx::vrpn;
using thx::vrpn::transcript::hex;

namespace {

using Bytes = std::vector<std::uint8_t>;

using thx::vrpn::test::body;

// Every size but `good` in [0, good + 16] is rejected with kPayloadSize.
template <class M>
void expectOnlySize(std::size_t good) {
  for (std::size_t n = 0; n <= good + 16; ++n) {
    Result<M> r = M::decode(Bytes(n, 0));
    if (n == good) {
      EXPECT_TRUE(r) << M::kTypeName << " " << n;
    } else {
      ASSERT_FALSE(r) << M::kTypeName << " " << n;
      EXPECT_EQ(r.error().code, ErrorCode::kPayloadSize);
    }
  }
}

// Identity: position (0, 0, 0), quaternion (x, y, z, w) = (0, 0, 0, 1); 1.0 = 3ff0000000000000.
constexpr std::string_view kIdentityPosQuat =
    "00 00 00 00 00 00 00 00  00 00 00 00 00 00 00 00  00 00 00 00 00 00 00 00"  // pos
    "00 00 00 00 00 00 00 00  00 00 00 00 00 00 00 00  00 00 00 00 00 00 00 00"  // quat x, y, z
    "3f f0 00 00 00 00 00 00";                                                   // quat w

}  // namespace

TEST(VrpnTrackerTransform, TypeNamesAreTheStockOnes) {
  EXPECT_EQ(TrackerToRoom::kTypeName, "vrpn_Tracker To_Room");
  EXPECT_EQ(TrackerUnitToSensor::kTypeName, "vrpn_Tracker Unit_To_Sensor");
  EXPECT_EQ(TrackerWorkspace::kTypeName, "vrpn_Tracker Workspace");
  EXPECT_EQ(TrackerRequestToRoom::kTypeName, "vrpn_Tracker Request_Tracker_To_Room");
  EXPECT_EQ(TrackerRequestUnitToSensor::kTypeName, "vrpn_Tracker Request_Unit_To_Sensor");
  EXPECT_EQ(TrackerRequestWorkspace::kTypeName, "vrpn_Tracker Request_Tracker_Workspace");
}

TEST(VrpnTrackerTransform, ToRoomIdentityIs56Bytes) {
  const Bytes expected = hex(kIdentityPosQuat);
  ASSERT_EQ(expected.size(), 56u);
  EXPECT_EQ(body(TrackerToRoom{}), expected);
  Result<TrackerToRoom> back = TrackerToRoom::decode(expected);
  ASSERT_TRUE(back) << back.error().reason;
  EXPECT_EQ(*back, TrackerToRoom{});
  expectOnlySize<TrackerToRoom>(56);
}

TEST(VrpnTrackerTransform, UnitToSensorHasTheSensorThenAZeroPad) {
  const Bytes identity0 = transcript::concat({hex("00 00 00 00  00 00 00 00"), hex(kIdentityPosQuat)});
  ASSERT_EQ(identity0.size(), 64u);
  EXPECT_EQ(body(TrackerUnitToSensor{}), identity0);

  // Sensor 3, pos (0.5, 0, -2), quat (0, 0, 0, 1): the pad word stays 0 (docs/vrpn.md §7).
  TrackerUnitToSensor m;
  m.sensor = 3;
  m.pos = {0.5, 0.0, -2.0};
  const Bytes expected = transcript::concat({hex("00 00 00 03  00 00 00 00"
                                                 "3f e0 00 00 00 00 00 00  00 00 00 00 00 00 00 00"
                                                 "c0 00 00 00 00 00 00 00"
                                                 "00 00 00 00 00 00 00 00  00 00 00 00 00 00 00 00"
                                                 "00 00 00 00 00 00 00 00  3f f0 00 00 00 00 00 00")});
  EXPECT_EQ(body(m), expected);
  Result<TrackerUnitToSensor> back = TrackerUnitToSensor::decode(expected);
  ASSERT_TRUE(back) << back.error().reason;
  EXPECT_EQ(*back, m);

  // Input: the pad is ignored; a negative sensor is an error, as in the stock Remote.
  Bytes padded = expected;
  padded[7] = 0x03;
  EXPECT_EQ(*TrackerUnitToSensor::decode(padded), m);
  Bytes negative = expected;
  negative[0] = 0xff;
  ASSERT_FALSE(TrackerUnitToSensor::decode(negative));
  EXPECT_EQ(TrackerUnitToSensor::decode(negative).error().code, ErrorCode::kBadValue);
  expectOnlySize<TrackerUnitToSensor>(64);
}

TEST(VrpnTrackerTransform, WorkspaceIsMinThenMax) {
  TrackerWorkspace m;
  m.min = {-0.1, -0.1, -0.1};
  m.max = {0.1, 0.1, 0.1};
  const Bytes expected = hex(
      "bf b9 99 99 99 99 99 9a  bf b9 99 99 99 99 99 9a  bf b9 99 99 99 99 99 9a"   // min = -0.1
      "3f b9 99 99 99 99 99 9a  3f b9 99 99 99 99 99 9a  3f b9 99 99 99 99 99 9a");  // max = 0.1
  ASSERT_EQ(expected.size(), 48u);
  EXPECT_EQ(body(m), expected);
  Result<TrackerWorkspace> back = TrackerWorkspace::decode(expected);
  ASSERT_TRUE(back) << back.error().reason;
  EXPECT_EQ(*back, m);
  expectOnlySize<TrackerWorkspace>(48);
}

TEST(VrpnTrackerTransform, RequestsAreEmpty) {
  EXPECT_TRUE(body(TrackerRequestToRoom{}).empty());
  EXPECT_TRUE(body(TrackerRequestUnitToSensor{}).empty());
  EXPECT_TRUE(body(TrackerRequestWorkspace{}).empty());
  expectOnlySize<TrackerRequestToRoom>(0);
  expectOnlySize<TrackerRequestUnitToSensor>(0);
  expectOnlySize<TrackerRequestWorkspace>(0);
}

// A whole reply frame: length word = 24 + body, the body already a multiple of 8 (no padding).
TEST(VrpnTrackerTransform, ReplyFramesAreByteExact) {
  const Header h{0, TimeValue{0x6b022912, 0x000b5c88}, 3, 8, 42};
  Bytes out;
  ASSERT_TRUE(appendFrame(out, h, body(TrackerUnitToSensor{})));
  const Bytes expected = transcript::concat({hex("00 00 00 58  6b 02 29 12  00 0b 5c 88  00 00 00 03  00 00 00 08"
                                                 "00 00 00 2a"
                                                 "00 00 00 00  00 00 00 00"),
                                             hex(kIdentityPosQuat)});
  EXPECT_EQ(out, expected);
  FrameDecoder d;
  d.feed(out);
  DecodeStep step = d.next();
  ASSERT_TRUE(std::holds_alternative<Frame>(step));
  EXPECT_EQ(std::get<Frame>(step).header.payload_length, 64u);
  EXPECT_EQ(*TrackerUnitToSensor::decode(std::get<Frame>(step).payload), TrackerUnitToSensor{});

  Bytes request;
  ASSERT_TRUE(appendFrame(request, Header{0, TimeValue{1, 2}, 3, 9, 0}, body(TrackerRequestWorkspace{})));
  EXPECT_EQ(request, hex("00 00 00 18  00 00 00 01  00 00 00 02  00 00 00 03  00 00 00 09  00 00 00 00"));
}

}  // namespace test_tracker_transform_messages
