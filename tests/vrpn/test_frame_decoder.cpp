// Framing: header layout, zero padding on output, padding ignored on input, chunking at every
// split point, truncation, and length limits enforced before any payload is buffered.
#include <gtest/gtest.h>

#include <string>

#include "device/vrpn/frame_decoder.hpp"
#include "tests/vrpn/transcripts.hpp"

namespace test_frame_decoder {

using namespace thx::vrpn;
using thx::vrpn::transcript::hex;
namespace tx = thx::vrpn::transcript;

namespace {

using Bytes = std::vector<std::uint8_t>;

// Every frame the decoder yields, as header + payload copies, then NeedMore or the error.
struct Drained {
  std::vector<std::pair<Header, Bytes>> frames;
  std::optional<Error> error;
};

void drain(FrameDecoder& d, Drained& out) {
  for (;;) {
    DecodeStep step = d.next();
    if (std::holds_alternative<NeedMore>(step)) return;
    if (auto* e = std::get_if<Error>(&step)) {
      out.error = *e;
      return;
    }
    const Frame& f = std::get<Frame>(step);
    out.frames.emplace_back(f.header, Bytes(f.payload.begin(), f.payload.end()));
  }
}

Drained decodeInChunks(const Bytes& bytes, const std::vector<std::size_t>& cuts) {
  FrameDecoder d;
  Drained out;
  std::size_t begin = 0;
  for (std::size_t cut : cuts) {
    d.feed(std::span(bytes).subspan(begin, cut - begin));
    drain(d, out);
    begin = cut;
  }
  d.feed(std::span(bytes).subspan(begin));
  drain(d, out);
  return out;
}

// The captured messages back to back (the cookie is not a message).
Bytes capturedStream() {
  return tx::concat({hex(tx::kUdpDescription), hex(tx::kSenderVrpnControl), hex(tx::kTypePosQuat), hex(tx::kPosQuat),
                     hex(tx::kButtonStates), hex(tx::kPing), hex(tx::kPong), hex(tx::kPlane)});
}

Bytes headerWithLength(std::uint32_t length) {
  Bytes b;
  ByteWriter w(b);
  w.u32(length);
  w.zeros(20);
  return b;
}

}  // namespace

TEST(Header, PaddingRule) {
  EXPECT_EQ(paddedLength(0), 0u);
  EXPECT_EQ(paddedLength(1), 8u);
  EXPECT_EQ(paddedLength(8), 8u);
  EXPECT_EQ(paddedLength(12), 16u);  // not the "len + len % 8" of Format_Of_Protocol.txt
  EXPECT_EQ(paddedLength(17), 24u);
  EXPECT_EQ(frameSize(64), 88u);
}

TEST(Header, RoundTripsAllFieldsBigEndian) {
  const Header h{12, TimeValue{0x01020304, 0x05060708}, -1, -2, 0xa0b0c0d0};
  Bytes b;
  ByteWriter w(b);
  writeHeader(w, h);
  EXPECT_EQ(b, hex("00 00 00 24 01 02 03 04 05 06 07 08 ff ff ff ff ff ff ff fe a0 b0 c0 d0"));
  Result<Header> back = decodeHeader(b);
  ASSERT_TRUE(back);
  EXPECT_EQ(*back, h);
}

TEST(Frame, PaddingIsZeroOnOutput) {
  Bytes out(3, 0xee);  // appends after what is there
  ASSERT_TRUE(appendFrame(out, Header{999, {}, 1, 2, 3}, hex("aa bb cc")));
  ASSERT_EQ(out.size(), 3u + 24u + 8u);
  EXPECT_EQ(out[3 + 3], 0x1b);  // length = 24 + 3, whatever payload_length said
  EXPECT_EQ(Bytes(out.end() - 8, out.end()), hex("aa bb cc 00 00 00 00 00"));
}

TEST(Frame, RefusesPayloadsOverTheLimit) {
  Bytes out;
  EXPECT_FALSE(appendFrame(out, Header{}, Bytes(kMaxPayloadLength + 1, 0)));
  EXPECT_TRUE(out.empty());
  EXPECT_TRUE(appendFrame(out, Header{}, Bytes(kMaxPayloadLength, 0)));
  EXPECT_EQ(out.size(), kMaxFrameLength);
}

TEST(FrameDecoder, DecodesTheCapturedStreamWhole) {
  const Drained d = decodeInChunks(capturedStream(), {});
  ASSERT_FALSE(d.error);
  ASSERT_EQ(d.frames.size(), 8u);
  EXPECT_EQ(d.frames[0].first.type, -3);
  EXPECT_EQ(d.frames[3].first.payload_length, 64u);
  EXPECT_EQ(d.frames[4].second, hex("00 00 00 02 00 00 00 01 00 00 00 01"));  // "trol" padding dropped
  EXPECT_EQ(d.frames[7].first.sequence, 58u);
}

TEST(FrameDecoder, EverySplitPointGivesTheSameFrames) {
  const Bytes stream = capturedStream();
  const Drained whole = decodeInChunks(stream, {});
  for (std::size_t cut = 0; cut <= stream.size(); ++cut) {
    const Drained split = decodeInChunks(stream, {cut});
    ASSERT_FALSE(split.error) << cut;
    ASSERT_EQ(split.frames, whole.frames) << "split at " << cut;
  }
}

TEST(FrameDecoder, EveryPairOfSplitPointsInOneMessage) {
  const Bytes stream = tx::concat({hex(tx::kPosQuat), hex(tx::kButtonStates)});
  const Drained whole = decodeInChunks(stream, {});
  for (std::size_t a = 0; a <= stream.size(); ++a)
    for (std::size_t b = a; b <= stream.size(); ++b) ASSERT_EQ(decodeInChunks(stream, {a, b}).frames, whole.frames);
}

TEST(FrameDecoder, OneByteAtATime) {
  const Bytes stream = capturedStream();
  std::vector<std::size_t> cuts;
  for (std::size_t i = 1; i < stream.size(); ++i) cuts.push_back(i);
  EXPECT_EQ(decodeInChunks(stream, cuts).frames, decodeInChunks(stream, {}).frames);
}

TEST(FrameDecoder, TruncatedInputWaitsThenReportsAtEnd) {
  const Bytes msg = hex(tx::kPlane);
  for (std::size_t n = 0; n < msg.size(); ++n) {
    FrameDecoder d;
    d.feed(std::span(msg).first(n));
    EXPECT_TRUE(std::holds_alternative<NeedMore>(d.next())) << n;
    EXPECT_EQ(d.buffered(), n);
    const std::optional<Error> end = d.finish();
    if (n == 0) {
      EXPECT_FALSE(end);
    } else {
      ASSERT_TRUE(end) << n;
      EXPECT_EQ(end->code, ErrorCode::kTruncated);
    }
  }
}

TEST(FrameDecoder, PaddingMustArriveBeforeTheMessageIsComplete) {
  // Button States counts 36 bytes but occupies 40: the message is not whole before the padding.
  const Bytes msg = hex(tx::kButtonStates);
  FrameDecoder d;
  d.feed(std::span(msg).first(36));
  EXPECT_TRUE(std::holds_alternative<NeedMore>(d.next()));
  d.feed(std::span(msg).subspan(36));
  EXPECT_TRUE(std::holds_alternative<Frame>(d.next()));
  EXPECT_FALSE(d.finish());
}

TEST(FrameDecoder, LengthBelowHeaderIsAnError) {
  for (std::uint32_t length : {0u, 1u, 23u}) {
    FrameDecoder d;
    d.feed(headerWithLength(length));
    DecodeStep step = d.next();
    ASSERT_TRUE(std::holds_alternative<Error>(step)) << length;
    EXPECT_EQ(std::get<Error>(step).code, ErrorCode::kLengthTooSmall);
  }
}

TEST(FrameDecoder, OversizedLengthIsRejectedFromTheHeaderAlone) {
  for (std::uint32_t length : {std::uint32_t(kMaxFrameLength + 1), 0x7fffffffu, 0xffffffffu}) {
    FrameDecoder d;
    d.feed(headerWithLength(length));  // no payload needed to decide
    DecodeStep step = d.next();
    ASSERT_TRUE(std::holds_alternative<Error>(step)) << length;
    EXPECT_EQ(std::get<Error>(step).code, ErrorCode::kLengthTooLarge);
    EXPECT_NE(std::get<Error>(step).reason.find(std::to_string(length)), std::string::npos);
  }
}

TEST(FrameDecoder, LargestLegalMessageIsAccepted) {
  Bytes msg = headerWithLength(std::uint32_t(kMaxFrameLength));
  msg.resize(kMaxFrameLength, 0x5a);
  FrameDecoder d;
  d.feed(msg);
  DecodeStep step = d.next();
  ASSERT_TRUE(std::holds_alternative<Frame>(step));
  EXPECT_EQ(std::get<Frame>(step).payload.size(), kMaxPayloadLength);
}

TEST(FrameDecoder, ErrorsAreSticky) {
  FrameDecoder d;
  d.feed(headerWithLength(3));
  ASSERT_TRUE(std::holds_alternative<Error>(d.next()));
  d.feed(hex(tx::kPing));
  EXPECT_TRUE(std::holds_alternative<Error>(d.next()));
  ASSERT_TRUE(d.error());
  EXPECT_EQ(d.finish()->code, ErrorCode::kLengthTooSmall);
}

TEST(FrameDecoder, GoodMessagesBeforeABadOneAreDelivered) {
  const Bytes stream = tx::concat({hex(tx::kPing), hex(tx::kPong), headerWithLength(0xffff0000u)});
  const Drained d = decodeInChunks(stream, {});
  EXPECT_EQ(d.frames.size(), 2u);
  ASSERT_TRUE(d.error);
  EXPECT_EQ(d.error->code, ErrorCode::kLengthTooLarge);
}

}  // namespace test_frame_decoder
