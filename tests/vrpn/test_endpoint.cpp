// Endpoint: the handshake, descriptions at any time, mapping by name, skipping what we don't
// know, dropping on malformed input, and the output queue, all driven byte by byte.
#include <gtest/gtest.h>

#include "device/vrpn/base_messages.hpp"
#include "device/vrpn/button_messages.hpp"
#include "device/vrpn/force_messages.hpp"
#include "device/vrpn/tracker_messages.hpp"
#include "tests/vrpn/endpoint_harness.hpp"
#include "tests/vrpn/transcripts.hpp"

namespace test_endpoint {

using namespace thx::vrpn;
using namespace thx::vrpn::harness;
using thx::vrpn::transcript::hex;
namespace tx = thx::vrpn::transcript;

namespace {

// What a stock vrpn_server sends a new client, built around the captured messages: cookie,
// UDP_DESCRIPTION (to be ignored), descriptions (some captured, some ours), a Pos_Quat and a
// Button States report, and a pong whose type it never described (to be skipped).
Bytes stockServerStream() {
  return tx::concat({hex(tx::kCookie), hex(tx::kUdpDescription), hex(tx::kSenderVrpnControl), senderDesc(1, "Tracker0"),
                     senderDesc(2, "Button0"), hex(tx::kTypePosQuat), typeDesc(19, ButtonStates::kTypeName),
                     hex(tx::kPosQuat), hex(tx::kButtonStates), hex(tx::kPong)});
}

// A client interested in Tracker0 and Button0.
struct Client {
  Endpoint e{fixedClock()};
  std::int32_t tracker = e.addSender("Tracker0");
  std::int32_t button = e.addSender("Button0");
  std::int32_t pos_quat = e.addType(TrackerPosQuat::kTypeName);
  std::int32_t states = e.addType(ButtonStates::kTypeName);
};

const std::vector<std::string> kStockServerEvents = {
    "connected log=0 minor_differs=0",
    "msg Tracker0/vrpn_Tracker Pos_Quat ids 1/4 seq 3 t 1795303698.773798 "
    "00000000000000000000000000000000000000000000000000000000000000000000000000000000"
    "3fec8f7da5526f2d00000000000000003fdcdd715b5d9922",
    "msg Button0/vrpn_Button States ids 2/5 seq 31 t 1795303731.305223 000000020000000100000001",
};

std::vector<std::size_t> everyByte(std::size_t n) {
  std::vector<std::size_t> cuts;
  for (std::size_t i = 1; i < n; ++i) cuts.push_back(i);
  return cuts;
}

}  // namespace

TEST(Endpoint, CookieIsQueuedAtOnceAndNothingElseBeforeThePeers) {
  Endpoint e(fixedClock());
  EXPECT_EQ(Bytes(e.pendingOutput().begin(), e.pendingOutput().end()), hex(tx::kCookie));
  EXPECT_EQ(e.state(), Endpoint::State::kHandshake);
  const Bytes cookie = hex(tx::kCookie);
  e.feed(std::span(cookie).first(23));
  EXPECT_FALSE(e.poll());
  EXPECT_EQ(e.pendingOutput().size(), 24u);
}

TEST(Endpoint, DecodesAStockServerStream) {
  Client c;
  const Bytes stream = stockServerStream();
  EXPECT_EQ(feedInChunks(c.e, stream), kStockServerEvents);
  EXPECT_EQ(c.e.state(), Endpoint::State::kConnected);
  EXPECT_EQ(c.e.stats().system_ignored, 1u);  // UDP_DESCRIPTION: we are TCP-only
  EXPECT_EQ(c.e.stats().descriptions_in, 5u);
  EXPECT_EQ(c.e.stats().skipped_undescribed, 1u);  // the pong: type 17 never described
  EXPECT_EQ(c.e.stats().delivered, 2u);
  EXPECT_EQ(c.e.stats().bytes_in, stream.size());
}

TEST(Endpoint, EverySplitPointOfTheStreamGivesTheSameEvents) {
  const Bytes stream = stockServerStream();
  for (std::size_t cut = 0; cut <= stream.size(); ++cut) {
    Client c;
    ASSERT_EQ(feedInChunks(c.e, stream, {cut}), kStockServerEvents) << "split at " << cut;
  }
}

TEST(Endpoint, OneByteAtATime) {
  const Bytes stream = stockServerStream();
  Client c;
  EXPECT_EQ(feedInChunks(c.e, stream, everyByte(stream.size())), kStockServerEvents);
}

TEST(Endpoint, DescribesEveryLocalNameInIdOrderAfterThePeersCookie) {
  Client c;
  const Bytes cookie = hex(tx::kCookie);
  c.e.feed(cookie);
  ASSERT_TRUE(c.e.poll());
  const auto out = c.e.pendingOutput();
  EXPECT_EQ(Bytes(out.begin(), out.begin() + 24), cookie);

  FrameDecoder d;
  d.feed(out.subspan(24));
  std::vector<std::string> got;
  std::uint32_t seq = 0;
  for (DecodeStep s = d.next(); std::holds_alternative<Frame>(s); s = d.next()) {
    const Frame& f = std::get<Frame>(s);
    EXPECT_EQ(f.header.sequence, seq++);
    EXPECT_EQ(f.header.time, (TimeValue{100, 200}));
    got.push_back(std::to_string(f.header.type) + " " + std::to_string(f.header.sender) + " " +
                  std::string(*decodeDescription(f.payload)));
  }
  EXPECT_EQ(d.buffered(), 0u);
  EXPECT_EQ(got, (std::vector<std::string>{
                     "-1 0 VRPN Control", "-1 1 Tracker0", "-1 2 Button0", "-2 0 VRPN_Connection_Got_First_Connection",
                     "-2 1 VRPN_Connection_Got_Connection", "-2 2 VRPN_Connection_Dropped_Connection",
                     "-2 3 VRPN_Connection_Dropped_Last_Connection", "-2 4 vrpn_Tracker Pos_Quat",
                     "-2 5 vrpn_Button States"}));
}

TEST(Endpoint, OurControlDescriptionMatchesTheCaptureExceptItsSequence) {
  // The capture's VRPN Control description was the server's second message (seq 1, after its
  // UDP_DESCRIPTION); we are TCP-only, so ours is the first.
  Endpoint e(fixedClock(TimeValue{0x6b022912, 0x000b5c86}));
  e.feed(hex(tx::kCookie));
  ASSERT_TRUE(e.poll());
  Bytes expected = hex(tx::kSenderVrpnControl);
  expected[23] = 0;  // seq 1 -> 0
  const auto out = e.pendingOutput().subspan(24, expected.size());
  EXPECT_EQ(Bytes(out.begin(), out.end()), expected);
}

TEST(Endpoint, MessageBeforeItsDescriptionIsSkippedThenDelivered) {
  Client c;
  const Bytes pq = body(TrackerPosQuat{});
  const Bytes stream = tx::concat({hex(tx::kCookie), senderDesc(1, "Tracker0"), message(1, 4, pq, 0),
                                   typeDesc(4, TrackerPosQuat::kTypeName), message(1, 4, pq, 1)});
  const auto events = feedInChunks(c.e, stream);
  ASSERT_EQ(events.size(), 2u);
  EXPECT_NE(events[1].find("seq 1"), std::string::npos);
  EXPECT_EQ(c.e.stats().skipped_undescribed, 1u);
}

TEST(Endpoint, DescriptionsTwiceAndEchoesAreHarmless) {
  Client c;
  const Bytes pq = body(TrackerPosQuat{});
  const Bytes stream = tx::concat({hex(tx::kCookie), senderDesc(1, "Tracker0"), typeDesc(4, TrackerPosQuat::kTypeName),
                                   message(1, 4, pq), senderDesc(1, "Tracker0"), typeDesc(4, TrackerPosQuat::kTypeName),
                                   typeDesc(4, TrackerPosQuat::kTypeName), message(1, 4, pq)});
  const auto events = feedInChunks(c.e, stream);
  EXPECT_EQ(events.size(), 3u);
  EXPECT_EQ(c.e.stats().descriptions_in, 5u);
  EXPECT_EQ(c.e.state(), Endpoint::State::kConnected);
}

TEST(Endpoint, MapsByNameNeverById) {
  // The peer's ids differ from ours and from the stock server's: only names count.
  Client c;
  const Bytes pq = body(TrackerPosQuat{});
  const Bytes stream = tx::concat({hex(tx::kCookie), senderDesc(77, "Tracker0"),
                                   typeDesc(1234, ButtonStates::kTypeName), typeDesc(0, TrackerPosQuat::kTypeName),
                                   message(77, 0, pq), message(77, 1234, body(ButtonStates{{1}}))});
  const auto events = feedInChunks(c.e, stream);
  ASSERT_EQ(events.size(), 3u);
  EXPECT_EQ(events[1].substr(0, 47), "msg Tracker0/vrpn_Tracker Pos_Quat ids 1/4 seq ");
  EXPECT_EQ(events[2].substr(0, 41), "msg Tracker0/vrpn_Button States ids 1/5 s");
}

TEST(Endpoint, RedescribedIdFollowsTheNewName) {
  Client c;
  const Bytes stream = tx::concat({hex(tx::kCookie), senderDesc(1, "Button0"), typeDesc(4, TrackerPosQuat::kTypeName),
                                   typeDesc(4, ButtonStates::kTypeName), message(1, 4, body(ButtonStates{{0}}))});
  const auto events = feedInChunks(c.e, stream);
  ASSERT_EQ(events.size(), 2u);
  EXPECT_NE(events[1].find("Button0/vrpn_Button States"), std::string::npos);
}

TEST(Endpoint, UnknownTypesSendersAndSystemMessagesAreSkipped) {
  Client c;
  const Bytes stream = tx::concat({
      hex(tx::kCookie), senderDesc(1, "Tracker0"), senderDesc(2, "Someone Else"),
      typeDesc(4, TrackerPosQuat::kTypeName), typeDesc(6, "vrpn_Tracker Acceleration"),
      message(1, 6, Bytes(72, 0)),  // described type we never registered
      message(2, 4, Bytes(64, 0)),  // described sender we never registered
      message(3, 4, Bytes(64, 0)),  // undescribed sender
      message(1, 5, Bytes(8, 0)),   // undescribed type
      message(0, -9, Bytes(5, 1)),  // unknown system type
      message(3, kLogDescription, Bytes(10, 0)), message(0, kDisconnectMessage, {}),
      message(1, 4, body(TrackerPosQuat{})),  // still in sync afterwards
  });
  const auto events = feedInChunks(c.e, stream);
  ASSERT_EQ(events.size(), 2u);
  EXPECT_NE(events[1].find("Tracker0/vrpn_Tracker Pos_Quat"), std::string::npos);
  EXPECT_EQ(c.e.stats().skipped_unknown, 2u);
  EXPECT_EQ(c.e.stats().skipped_undescribed, 2u);
  EXPECT_EQ(c.e.stats().system_ignored, 3u);
}

TEST(Endpoint, MinorVersionDifferenceConnects) {
  Endpoint e(fixedClock());
  Bytes cookie = hex(tx::kCookie);
  cookie[15] = '5';
  cookie[18] = '3';
  EXPECT_EQ(feedInChunks(e, cookie), (std::vector<std::string>{"connected log=3 minor_differs=1"}));
  ASSERT_TRUE(e.peer());
  EXPECT_EQ(e.peer()->version, "vrpn: ver. 07.35");
}

TEST(Endpoint, BadCookieDropsAndDescribesNothing) {
  for (auto [index, value, code] :
       {std::tuple{12, '8', ErrorCode::kBadCookie}, std::tuple{0, 'V', ErrorCode::kBadCookie},
        std::tuple{18, '7', ErrorCode::kBadLogMode}}) {
    Endpoint e(fixedClock());
    Bytes cookie = hex(tx::kCookie);
    cookie[std::size_t(index)] = std::uint8_t(value);
    const Bytes stream = tx::concat({cookie, senderDesc(1, "Tracker0")});
    EXPECT_EQ(feedInChunks(e, stream), (std::vector<std::string>{"dropped " + std::string(toString(code))}));
    EXPECT_EQ(e.pendingOutput().size(), 24u);  // only our cookie
    ASSERT_TRUE(e.error());
    EXPECT_EQ(e.error()->code, code);
  }
}

TEST(Endpoint, MalformedInputDropsWithAReason) {
  Bytes big_desc;
  {
    ByteWriter w(big_desc);
    w.u32(97);
    w.zeros(97);  // 101-byte body
  }
  Bytes bad_len_word;
  {
    ByteWriter w(bad_len_word);
    w.u32(9);
    w.chars("Tracker0");  // 8 bytes where the word says 9
  }
  Bytes oversized;
  {
    ByteWriter w(oversized);
    w.u32(0x10000000);
    w.zeros(20);
  }
  const std::vector<std::pair<Bytes, ErrorCode>> cases = {
      {senderDesc(kMaxNames, "Tracker0"), ErrorCode::kIdOutOfRange},
      {typeDesc(-1, "x"), ErrorCode::kIdOutOfRange},
      {message(1, kSenderDescription, big_desc), ErrorCode::kBadDescription},
      {message(1, kTypeDescription, bad_len_word), ErrorCode::kBadDescription},
      {message(1, kTypeDescription, hex("00 00 00 01 00")), ErrorCode::kBadDescription},  // empty name
      {message(1, kTypeDescription, hex("00 00")), ErrorCode::kBadDescription},
      {oversized, ErrorCode::kLengthTooLarge},
      {hex("00 00 00 10 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00"), ErrorCode::kLengthTooSmall},
  };
  for (const auto& [bad, code] : cases) {
    Client c;
    const Bytes stream = tx::concat({hex(tx::kCookie), senderDesc(1, "Tracker0"), bad, senderDesc(2, "Button0")});
    const auto events = feedInChunks(c.e, stream, everyByte(stream.size()));
    ASSERT_EQ(events.size(), 2u) << toString(code);
    EXPECT_EQ(events[1], "dropped " + std::string(toString(code)));
    EXPECT_FALSE(c.e.error()->reason.empty());
  }
}

TEST(Endpoint, AfterADropNothingMoves) {
  Client c;
  feedInChunks(c.e, tx::concat({hex(tx::kCookie), message(1, 4, {}, 0)}));
  c.e.drop(Error{ErrorCode::kPayloadSize, "owner says so"});
  EXPECT_EQ(feedInChunks(c.e, {}), (std::vector<std::string>{"dropped payload size"}));
  EXPECT_EQ(c.e.error()->reason, "owner says so");
  const std::uint64_t in = c.e.stats().bytes_in;
  const std::size_t out = c.e.pendingOutput().size();
  EXPECT_TRUE(feedInChunks(c.e, hex(tx::kPosQuat)).empty());
  EXPECT_EQ(c.e.stats().bytes_in, in);
  EXPECT_FALSE(c.e.sendMessage(c.tracker, TrackerPosQuat{}));
  EXPECT_EQ(c.e.pendingOutput().size(), out);
  EXPECT_FALSE(c.e.poll());
}

TEST(Endpoint, TruncatedInputIsReportedAtEndOfStream) {
  {
    Endpoint e(fixedClock());
    const Bytes cookie = hex(tx::kCookie);
    e.feed(std::span(cookie).first(10));
    e.finishInput();
    EXPECT_EQ(feedInChunks(e, {}), (std::vector<std::string>{"dropped truncated"}));
  }
  {
    Client c;
    const Bytes stream = tx::concat({hex(tx::kCookie), senderDesc(1, "Tracker0")});
    feedInChunks(c.e, std::span(stream).first(stream.size() - 3));
    c.e.finishInput();
    EXPECT_EQ(feedInChunks(c.e, {}), (std::vector<std::string>{"dropped truncated"}));
  }
  {
    Client c;
    feedInChunks(c.e, tx::concat({hex(tx::kCookie), senderDesc(1, "Tracker0")}));
    c.e.finishInput();  // a clean end between messages
    EXPECT_EQ(feedInChunks(c.e, {}), (std::vector<std::string>{"dropped peer closed"}));
  }
}

TEST(Endpoint, MessagesFedBeforeTheEndAreStillDelivered) {
  Client c;
  c.e.feed(tx::concat(
      {hex(tx::kCookie), senderDesc(1, "Tracker0"), typeDesc(4, TrackerPosQuat::kTypeName), hex(tx::kPosQuat)}));
  c.e.finishInput();
  c.e.feed(hex(tx::kPosQuat));  // nothing counts after the end
  const auto events = feedInChunks(c.e, {});
  ASSERT_EQ(events.size(), 3u);
  EXPECT_EQ(events[1].substr(0, 34), "msg Tracker0/vrpn_Tracker Pos_Quat");
  EXPECT_EQ(events[2], "dropped peer closed");
}

TEST(Endpoint, SendRulesAndSequenceNumbers) {
  Client c;
  EXPECT_FALSE(c.e.sendMessage(c.tracker, TrackerPosQuat{}));  // before the handshake
  feedInChunks(c.e, hex(tx::kCookie));
  c.e.consumeOutput(c.e.pendingOutput().size());
  EXPECT_FALSE(c.e.send(99, c.pos_quat, Bytes(64, 0)));  // unknown sender
  EXPECT_FALSE(c.e.send(c.tracker, 99, Bytes(64, 0)));   // unknown type
  EXPECT_TRUE(c.e.pendingOutput().empty());

  // 9 descriptions went out at the handshake (seq 0..8), so the next message is seq 9. A type
  // first used now is described right before it.
  ASSERT_TRUE(c.e.sendMessage(c.tracker, ForceScp{}, TimeValue{5, 6}));
  FrameDecoder d;
  d.feed(c.e.pendingOutput());
  auto first = std::get<Frame>(d.next());
  EXPECT_EQ(first.header.type, kTypeDescription);
  EXPECT_EQ(first.header.sender, 6);
  EXPECT_EQ(first.header.sequence, 9u);
  EXPECT_EQ(*decodeDescription(first.payload), ForceScp::kTypeName);
  auto second = std::get<Frame>(d.next());
  EXPECT_EQ(second.header.type, 6);
  EXPECT_EQ(second.header.sender, c.tracker);
  EXPECT_EQ(second.header.sequence, 10u);
  EXPECT_EQ(second.header.time, (TimeValue{5, 6}));
  EXPECT_EQ(Bytes(second.payload.begin(), second.payload.end()), body(ForceScp{}));
  EXPECT_EQ(c.e.stats().messages_out, 11u);
}

TEST(Endpoint, PartialWritesKeepTheStreamIntact) {
  Client c;
  feedInChunks(c.e, hex(tx::kCookie));
  for (int i = 0; i < 50; ++i) ASSERT_TRUE(c.e.sendMessage(c.tracker, TrackerPosQuat{}));
  Bytes written;
  while (!c.e.pendingOutput().empty()) {
    const auto chunk = c.e.pendingOutput().first(std::min<std::size_t>(7, c.e.pendingOutput().size()));
    written.insert(written.end(), chunk.begin(), chunk.end());
    c.e.consumeOutput(chunk.size());
  }
  FrameDecoder d;
  d.feed(std::span(written).subspan(24));
  int frames = 0;
  while (std::holds_alternative<Frame>(d.next())) ++frames;
  EXPECT_EQ(frames, 9 + 50);
  EXPECT_EQ(d.buffered(), 0u);
}

TEST(Endpoint, PeerThatStopsReadingIsDropped) {
  Endpoint::Options o = fixedClock();
  o.max_pending_output = 4096;
  Endpoint e(o);
  const std::int32_t me = e.addSender("Phantom0");
  feedInChunks(e, hex(tx::kCookie));
  int sent = 0;
  while (e.sendMessage(me, TrackerPosQuat{})) ++sent;
  EXPECT_GT(sent, 30);
  EXPECT_LE(e.pendingOutput().size(), 4096u);
  EXPECT_EQ(feedInChunks(e, {}), (std::vector<std::string>{"dropped output overflow"}));
}

TEST(Endpoint, ReadingPeerIsNeverDropped) {
  Endpoint::Options o = fixedClock();
  o.max_pending_output = 4096;
  Endpoint e(o);
  const std::int32_t me = e.addSender("Phantom0");
  feedInChunks(e, hex(tx::kCookie));
  for (int i = 0; i < 10000; ++i) {
    ASSERT_TRUE(e.sendMessage(me, TrackerPosQuat{}));
    e.consumeOutput(e.pendingOutput().size());
  }
  EXPECT_EQ(e.state(), Endpoint::State::kConnected);
}

TEST(Endpoint, TwoEndpointsTalk) {
  // Our server and our client in memory, 5-byte writes: handshake, States on connect, ping ->
  // pong + States, a Plane from the client, reports from the server.
  Endpoint server(fixedClock(TimeValue{1, 0}));
  Endpoint client(fixedClock(TimeValue{2, 0}));
  const std::int32_t s_dev = server.addSender("Phantom0");
  const std::int32_t c_dev = client.addSender("Phantom0");
  for (auto n : {Pong::kTypeName, ButtonStates::kTypeName, TrackerPosQuat::kTypeName}) client.addType(n);
  for (auto n : {Ping::kTypeName, ForcePlane::kTypeName}) server.addType(n);

  PipeEvents ev;
  pipe(server, client, ev, 5);
  ASSERT_EQ(ev.a.size(), 1u);
  ASSERT_EQ(ev.b.size(), 1u);
  EXPECT_EQ(ev.a[0], "connected log=0 minor_differs=0");
  ASSERT_TRUE(server.sendMessage(s_dev, ButtonStates{{0, 0}}));
  ASSERT_TRUE(client.sendMessage(c_dev, Ping{}));
  ForcePlane plane;
  plane.plane = {0.0f, 0.0f, 1.0f, 0.01f};
  plane.n_rec_cycles = 10;
  ASSERT_TRUE(client.sendMessage(c_dev, plane));
  pipe(server, client, ev, 5);
  ASSERT_EQ(ev.a.size(), 3u);
  EXPECT_NE(ev.a[1].find("Phantom0/vrpn_Base ping_message"), std::string::npos);
  EXPECT_EQ(ev.a[2].substr(0, 36), "msg Phantom0/vrpn_ForceDevice Plane ");
  EXPECT_NE(ev.a[2].find(hexOf(body(plane))), std::string::npos);
  ASSERT_EQ(ev.b.size(), 2u);
  EXPECT_NE(ev.b[1].find("Phantom0/vrpn_Button States"), std::string::npos);

  ASSERT_TRUE(server.sendMessage(s_dev, Pong{}));
  TrackerPosQuat report;
  report.pos = {0.01, 0.02, 0.03};
  ASSERT_TRUE(server.sendMessage(s_dev, report, TimeValue{9, 10}));
  pipe(server, client, ev, 5);
  ASSERT_EQ(ev.b.size(), 4u);
  EXPECT_NE(ev.b[2].find("vrpn_Base pong_message"), std::string::npos);
  EXPECT_NE(ev.b[3].find("t 9.10 " + hexOf(body(report))), std::string::npos);
  EXPECT_EQ(server.state(), Endpoint::State::kConnected);
  EXPECT_EQ(client.state(), Endpoint::State::kConnected);
}

}  // namespace test_endpoint
