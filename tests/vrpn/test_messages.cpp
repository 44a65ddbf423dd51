// Device message bodies (docs/vrpn.md §6-§9): field order and sizes on the wire, round trips, and
// the exact-size rule (one wrong-sized body is an error, never a partial read).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "tests/vrpn/message_body.hpp"
#include "device/vrpn/base_messages.hpp"
#include "device/vrpn/button_messages.hpp"
#include "device/vrpn/force_messages.hpp"
#include "device/vrpn/limits.hpp"
#include "device/vrpn/tracker_messages.hpp"
#include "tests/vrpn/transcripts.hpp"

namespace test_messages {

using namespace thx::vrpn;
using thx::vrpn::transcript::hex;

namespace {

using Bytes = std::vector<std::uint8_t>;

using thx::vrpn::test::body;

template <class M>
void expectRoundTrip(const M& m, std::size_t size) {
  const Bytes b = body(m);
  EXPECT_EQ(b.size(), size) << M::kTypeName;
  Result<M> back = M::decode(b);
  ASSERT_TRUE(back) << back.error().reason;
  EXPECT_EQ(*back, m) << M::kTypeName;
}

// Every size but `good` in [0, good + 16] is rejected with kPayloadSize.
template <class M>
void expectOnlySize(std::size_t good) {
  for (std::size_t n = 0; n <= good + 16; ++n) {
    const Bytes b(n, 0);
    Result<M> r = M::decode(b);
    if (n == good) {
      EXPECT_TRUE(r) << M::kTypeName << " " << n;
    } else {
      ASSERT_FALSE(r) << M::kTypeName << " " << n;
      EXPECT_EQ(r.error().code, ErrorCode::kPayloadSize);
      EXPECT_NE(r.error().reason.find(M::kTypeName), std::string::npos);
    }
  }
}

}  // namespace

TEST(ByteIo, FloatsAreBigEndianBitPatterns) {
  Bytes b;
  ByteWriter w(b);
  w.f32(1.0f);
  w.f64(1.0);
  w.i32(-2);
  EXPECT_EQ(b, hex("3f 80 00 00  3f f0 00 00 00 00 00 00  ff ff ff fe"));
  ByteReader r(b);
  EXPECT_EQ(r.f32(), 1.0f);
  EXPECT_EQ(r.f64(), 1.0);
  EXPECT_EQ(r.i32(), -2);
  EXPECT_TRUE(r.ok());
  EXPECT_EQ(r.u32(), 0u);  // past the end: zero, and latched
  EXPECT_FALSE(r.ok());
}

TEST(TrackerMessages, PosQuatRepeatsSensorInPadAndIgnoresItOnInput) {
  TrackerPosQuat m;
  m.sensor = 3;
  m.pos = {0.1, -0.2, 0.3};
  m.quat = {0.0, 0.0, std::sqrt(0.5), std::sqrt(0.5)};
  Bytes b = body(m);
  EXPECT_EQ(Bytes(b.begin(), b.begin() + 8), hex("00 00 00 03 00 00 00 03"));
  expectRoundTrip(m, 64);
  b[7] = 99;  // pad word
  EXPECT_EQ(*TrackerPosQuat::decode(b), m);
}

TEST(TrackerMessages, NegativeSensorIsRejected) {
  TrackerPosQuat p;
  p.sensor = -1;
  EXPECT_EQ(TrackerPosQuat::decode(body(p)).error().code, ErrorCode::kBadValue);
  TrackerVelocity v;
  v.sensor = -5;
  EXPECT_EQ(TrackerVelocity::decode(body(v)).error().code, ErrorCode::kBadValue);
}

TEST(TrackerMessages, VelocityLayout) {
  TrackerVelocity m;
  m.sensor = 1;
  m.vel = {1.0, 2.0, 3.0};
  m.vel_quat = {0.0, 0.0, 0.0, 1.0};
  m.vel_quat_dt = 0.5;
  const Bytes b = body(m);
  ASSERT_EQ(b.size(), 72u);
  EXPECT_EQ(Bytes(b.begin() + 8, b.begin() + 16), hex("3f f0 00 00 00 00 00 00"));   // vel x = 1
  EXPECT_EQ(Bytes(b.begin() + 56, b.begin() + 64), hex("3f f0 00 00 00 00 00 00"));  // quat w = 1
  EXPECT_EQ(Bytes(b.begin() + 64, b.end()), hex("3f e0 00 00 00 00 00 00"));         // dt = 0.5
  expectRoundTrip(m, 72);
}

TEST(TrackerMessages, ExactSizes) {
  expectOnlySize<TrackerPosQuat>(64);
  expectOnlySize<TrackerVelocity>(72);
  expectOnlySize<TrackerUpdateRate>(8);
  expectOnlySize<TrackerResetOrigin>(0);
  expectRoundTrip(TrackerUpdateRate{1000.0}, 8);
  EXPECT_EQ(body(TrackerUpdateRate{1000.0}), hex("40 8f 40 00 00 00 00 00"));
}

TEST(ButtonMessages, ChangeLayoutAndSize) {
  EXPECT_EQ(body(ButtonChange{1, 1}), hex("00 00 00 01 00 00 00 01"));
  expectRoundTrip(ButtonChange{0, 1}, 8);
  expectOnlySize<ButtonChange>(8);
}

TEST(ButtonMessages, StatesCountAndSizeMustAgree) {
  expectRoundTrip(ButtonStates{{}}, 4);
  expectRoundTrip(ButtonStates{{0, 1, 0}}, 16);
  // Count says 3, body holds 2.
  EXPECT_EQ(ButtonStates::decode(hex("00 00 00 03 00 00 00 01 00 00 00 01")).error().code, ErrorCode::kPayloadSize);
  // Count says 1, body holds 2.
  EXPECT_EQ(ButtonStates::decode(hex("00 00 00 01 00 00 00 01 00 00 00 01")).error().code, ErrorCode::kPayloadSize);
  EXPECT_EQ(ButtonStates::decode(hex("00 00 00")).error().code, ErrorCode::kPayloadSize);
  EXPECT_EQ(ButtonStates::decode(hex("ff ff ff ff")).error().code, ErrorCode::kBadValue);
}

TEST(ButtonMessages, AtMost256Buttons) {
  ButtonStates many;
  many.states.assign(kMaxButtons, 1);
  expectRoundTrip(many, 4 + 4 * kMaxButtons);
  // A count over the limit is refused before the body is even looked at.
  EXPECT_EQ(ButtonStates::decode(hex("00 00 01 01")).error().code, ErrorCode::kBadValue);
  EXPECT_EQ(ButtonStates::decode(hex("7f ff ff ff")).error().code, ErrorCode::kBadValue);
  // encode() never sends more than the limit.
  many.states.assign(kMaxButtons + 10, 0);
  EXPECT_EQ(body(many).size(), 4 + 4 * kMaxButtons);
}

TEST(ForceMessages, PlaneDefaultsAndStopSurface) {
  const ForcePlane defaults;
  EXPECT_EQ(defaults.kspring, 0.8f);
  EXPECT_EQ(defaults.kdamp, 0.001f);
  EXPECT_EQ(defaults.fdyn, 0.3f);
  EXPECT_EQ(defaults.fstat, 0.7f);
  EXPECT_EQ(defaults.n_rec_cycles, 1);

  ForcePlane p;
  p.plane = {0.0f, 0.0f, 1.0f, -0.02f};
  p.n_rec_cycles = 10;
  const ForcePlane stop = stopSurface(p);
  EXPECT_EQ(stop.plane, (std::array<float, 4>{0.0f, 0.0f, 0.0f, 0.0f}));
  EXPECT_EQ(stop.n_rec_cycles, 10);
  expectRoundTrip(p, 40);
  expectRoundTrip(stop, 40);
  expectOnlySize<ForcePlane>(40);
}

TEST(ForceMessages, Plane2Layout) {
  ForcePlane2 m{1.0f, 2.0f, 0.0f, 0.0f, 0.0f, 0.5f};
  EXPECT_EQ(body(m), hex("3f 80 00 00 40 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 3f 00 00 00"));
  expectRoundTrip(m, 24);
  expectOnlySize<ForcePlane2>(24);
}

TEST(ForceMessages, ForceFieldLayoutIsRowMajor) {
  ForceField f;
  f.origin = {1.0f, 0.0f, 0.0f};
  f.force = {0.0f, 2.0f, 0.0f};
  f.jacobian = {{{-1.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.5f}, {0.0f, 0.0f, 0.0f}}};
  f.radius = 100.0f;
  const Bytes b = body(f);
  ASSERT_EQ(b.size(), 64u);
  EXPECT_EQ(Bytes(b.begin(), b.begin() + 4), hex("3f 80 00 00"));        // origin x
  EXPECT_EQ(Bytes(b.begin() + 16, b.begin() + 20), hex("40 00 00 00"));  // force y
  EXPECT_EQ(Bytes(b.begin() + 24, b.begin() + 28), hex("bf 80 00 00"));  // J[0][0]
  EXPECT_EQ(Bytes(b.begin() + 44, b.begin() + 48), hex("3f 00 00 00"));  // J[1][2]
  EXPECT_EQ(Bytes(b.begin() + 60, b.end()), hex("42 c8 00 00"));         // radius
  expectRoundTrip(f, 64);
  expectOnlySize<ForceField>(64);
}

TEST(ForceMessages, CustomEffect) {
  ForceCustomEffect buzz{0, {0.5f, 100.0f, 0.25f}};
  EXPECT_EQ(body(buzz), hex("00 00 00 00 00 00 00 03 3f 00 00 00 42 c8 00 00 3e 80 00 00"));
  expectRoundTrip(buzz, 20);
  const ForceCustomEffect stop{ForceCustomEffect::kStopEffect, {}};
  EXPECT_EQ(body(stop), hex("ff ff ff ff 00 00 00 00"));
  expectRoundTrip(stop, 8);
}

TEST(ForceMessages, CustomEffectCountMustMatchTheBody) {
  EXPECT_EQ(ForceCustomEffect::decode(hex("00 00 00 00 00 00 00")).error().code, ErrorCode::kPayloadSize);
  EXPECT_EQ(ForceCustomEffect::decode(hex("00 00 00 00 00 00 00 01")).error().code, ErrorCode::kPayloadSize);
  EXPECT_EQ(ForceCustomEffect::decode(hex("00 00 00 00 00 00 00 00 3f")).error().code, ErrorCode::kPayloadSize);
  // A huge count in a small body: rejected by comparing against the body, no allocation.
  EXPECT_EQ(ForceCustomEffect::decode(hex("00 00 00 00 ff ff ff ff 00 00 00 00")).error().code,
            ErrorCode::kPayloadSize);
  EXPECT_EQ(ForceCustomEffect::decode(hex("00 00 00 00 40 00 00 01 00 00 00 00")).error().code,
            ErrorCode::kPayloadSize);
}

TEST(ForceMessages, Reports) {
  expectRoundTrip(ForceReport{{1.5, -2.0, 0.0}}, 24);
  expectOnlySize<ForceReport>(24);
  ForceScp scp;
  scp.pos = {0.01, 0.02, 0.03};
  expectRoundTrip(scp, 56);
  expectOnlySize<ForceScp>(56);
  expectRoundTrip(ForceError{2}, 4);
  expectOnlySize<ForceError>(4);
}

TEST(ForceMessages, NonFiniteValuesPassThroughBitExact) {
  // The codec does not judge values; the renderer must (a NaN plane must not reach a motor).
  ForcePlane p;
  p.plane = {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity(), 0.0f, -0.0f};
  const Bytes b = body(p);
  Result<ForcePlane> back = ForcePlane::decode(b);
  ASSERT_TRUE(back);
  EXPECT_TRUE(std::isnan(back->plane[0]));
  EXPECT_TRUE(std::isinf(back->plane[1]));
  EXPECT_EQ(body(*back), b);
}

TEST(BaseMessages, PingPongAreEmpty) {
  expectOnlySize<Ping>(0);
  expectOnlySize<Pong>(0);
}

TEST(BaseMessages, TextIsSentAsTheFullBuffer) {
  const TextMessage t{TextMessage::kWarning, 3, "plane ignored"};
  const Bytes b = body(t);
  ASSERT_EQ(b.size(), 8u + 1024u);
  EXPECT_EQ(Bytes(b.begin(), b.begin() + 8), hex("00 00 00 01 00 00 00 03"));
  EXPECT_EQ(std::string(b.begin() + 8, b.begin() + 21), "plane ignored");
  EXPECT_EQ(b[21], 0);
  expectRoundTrip(t, 1032);
}

TEST(BaseMessages, TextIsCutToTheBuffer) {
  const TextMessage t{TextMessage::kError, 0, std::string(2000, 'x')};
  Result<TextMessage> back = TextMessage::decode(body(t));
  ASSERT_TRUE(back);
  EXPECT_EQ(back->text.size(), 1023u);
}

TEST(BaseMessages, TextDecodesShortBodiesUpToTheNul) {
  Result<TextMessage> t = TextMessage::decode(hex("00 00 00 00 00 00 00 00 68 69 00 7a 7a"));
  ASSERT_TRUE(t);
  EXPECT_EQ(t->text, "hi");
  Result<TextMessage> no_nul = TextMessage::decode(hex("00 00 00 02 00 00 00 00 68 69"));
  ASSERT_TRUE(no_nul);
  EXPECT_EQ(no_nul->text, "hi");
  EXPECT_EQ(no_nul->severity, 2u);
  EXPECT_EQ(TextMessage::decode(hex("00 00 00 00 00 00 00")).error().code, ErrorCode::kPayloadSize);
  EXPECT_EQ(TextMessage::decode(Bytes(1033, 0)).error().code, ErrorCode::kPayloadSize);
}

}  // namespace test_messages
