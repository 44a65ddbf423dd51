// A short, deterministic mutation-fuzzing run of the decoder for CI (libFuzzer is optional, see
// docs/vrpn.md). Seeds are the captured transcripts and a stream of every message type we know;
// mutations are byte flips, interesting 32-bit words at word offsets (lengths, ids, counts),
// inserts, deletes, duplications, truncations and splices.
//
// The input sequence is fixed (fixed seed). The run always covers the first kMinIterations
// inputs, then continues through the same sequence until about 2 s have passed (so a sanitizer
// build, ~20x slower, still finishes quickly). THX_VRPN_FUZZ_ITERATIONS=N runs exactly N inputs.
// A failure prints its iteration and input as hex, which reproduces it anywhere.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <string>

#include "tests/fuzz/short_run.hpp"
#include "tests/vrpn/fuzz_decoder_body.hpp"
#include "tests/vrpn/transcripts.hpp"

namespace test_fuzz_decoder {

using namespace thx::vrpn;
using thx::vrpn::transcript::hex;
namespace tx = thx::vrpn::transcript;
using Bytes = std::vector<std::uint8_t>;

namespace {

// Everything a server and a client of ours send, as the peer receives it (cookie included).
Bytes everyMessageType() {
  Endpoint e(harness::fixedClock());
  const std::int32_t dev = e.addSender("Phantom0");
  const std::int32_t trk = e.addSender("Tracker0");
  e.feed(makeCookie());
  while (e.poll()) {
  }
  ForceField field;
  field.jacobian = {{{-100.0f, 0.0f, 0.0f}, {0.0f, -100.0f, 0.0f}, {0.0f, 0.0f, -100.0f}}};
  field.radius = 100.0f;
  e.sendMessage(dev, Ping{});
  e.sendMessage(dev, Pong{});
  e.sendMessage(dev, TextMessage{1, 0, "hello"});
  e.sendMessage(trk, TrackerPosQuat{1, {0.1, 0.2, 0.3}, {0.0, 0.0, 0.0, 1.0}});
  e.sendMessage(trk, TrackerVelocity{});
  e.sendMessage(dev, TrackerUpdateRate{1000.0});
  e.sendMessage(dev, TrackerResetOrigin{});
  e.sendMessage(dev, TrackerRequestToRoom{});
  e.sendMessage(dev, TrackerRequestUnitToSensor{});
  e.sendMessage(dev, TrackerRequestWorkspace{});
  e.sendMessage(trk, TrackerToRoom{});
  e.sendMessage(trk, TrackerUnitToSensor{});
  e.sendMessage(trk, TrackerWorkspace{{-0.1, -0.1, -0.1}, {0.1, 0.1, 0.1}});
  e.sendMessage(dev, ButtonChange{0, 1});
  e.sendMessage(dev, ButtonStates{{1, 0}});
  e.sendMessage(dev, ForcePlane{});
  e.sendMessage(dev, ForcePlane2{});
  e.sendMessage(dev, field);
  e.sendMessage(dev, ForceCustomEffect{0, {1.0f, 100.0f, 0.1f}});
  e.sendMessage(dev, ForceReport{});
  e.sendMessage(dev, ForceScp{});
  e.sendMessage(dev, ForceError{1});
  const auto out = e.pendingOutput();
  Bytes seed{0};  // mode 0: the stream carries its own cookie
  seed.insert(seed.end(), out.begin(), out.end());
  return seed;
}

std::vector<Bytes> seeds() {
  Bytes captured{1};  // mode 1: cookie prepended
  for (auto t : {tx::kUdpDescription, tx::kSenderVrpnControl, tx::kTypePosQuat, tx::kPosQuat, tx::kButtonStates,
                 tx::kPing, tx::kPong, tx::kPlane}) {
    const Bytes b = hex(t);
    captured.insert(captured.end(), b.begin(), b.end());
  }
  return {captured, everyMessageType(), Bytes{1}, Bytes{0}};
}

using thx::fuzz::Rng;  // the same fixed-seed generator as every short fuzz run

constexpr std::uint32_t kInterestingWords[] = {
    0,     1,    7,    8,   23,  24,         25,         31,         32,         63999,      64000,      64001,
    65536, 1999, 2000, 256, 257, 0x7fffffff, 0x80000000, 0xffffffff, 0xfffffffe, 0xfffffffd, 0xfffffffc, 0xfffffffb};

void mutate(Bytes& b, Rng& rng, const std::vector<Bytes>& pool) {
  const int rounds = 1 + int(rng.below(4));
  for (int i = 0; i < rounds; ++i) {
    const std::size_t n = b.size();
    switch (rng.below(8)) {
      case 0:  // flip a bit
        if (n > 1) b[1 + rng.below(n - 1)] ^= std::uint8_t(1u << rng.below(8));
        break;
      case 1:  // interesting word at a word-aligned offset of the stream (after the mode byte)
        if (n >= 5) {
          const std::size_t at = 1 + 4 * rng.below((n - 1) / 4);
          const std::uint32_t w = kInterestingWords[rng.below(std::size(kInterestingWords))];
          for (int k = 0; k < 4 && at + std::size_t(k) < n; ++k)
            b[at + std::size_t(k)] = std::uint8_t(w >> (24 - 8 * k));
        }
        break;
      case 2:  // random byte
        if (n > 1) b[1 + rng.below(n - 1)] = std::uint8_t(rng.next());
        break;
      case 3:  // insert a few bytes
        b.insert(b.begin() + std::ptrdiff_t(1 + rng.below(n)), 1 + rng.below(8), std::uint8_t(rng.next()));
        break;
      case 4:  // delete a range
        if (n > 2) {
          const std::size_t at = 1 + rng.below(n - 1);
          b.erase(b.begin() + std::ptrdiff_t(at), b.begin() + std::ptrdiff_t(std::min(n, at + 1 + rng.below(16))));
        }
        break;
      case 5:  // duplicate a range (repeated descriptions, repeated messages)
        if (n > 2 && n < 20000) {
          const std::size_t at = 1 + rng.below(n - 1);
          const std::size_t len = std::min(n - at, 1 + rng.below(96));
          const Bytes piece(b.begin() + std::ptrdiff_t(at), b.begin() + std::ptrdiff_t(at + len));
          b.insert(b.begin() + std::ptrdiff_t(1 + rng.below(n)), piece.begin(), piece.end());
        }
        break;
      case 6:  // truncate
        if (n > 1) b.resize(1 + rng.below(n));
        break;
      case 7: {  // splice the tail of another seed
        const Bytes& other = pool[rng.below(pool.size())];
        if (other.size() > 1) {
          const std::size_t from = 1 + rng.below(other.size() - 1);
          b.resize(1 + rng.below(n));
          b.insert(b.end(), other.begin() + std::ptrdiff_t(from), other.end());
        }
        break;
      }
    }
    if (b.empty()) b.push_back(0);
  }
  if (rng.below(4) == 0) b[0] = std::uint8_t(rng.next());  // mode and chunking
}

}  // namespace

// Writes the seeds as a libFuzzer corpus (docs/vrpn.md); skipped unless asked.
TEST(FuzzDecoder, WriteSeedCorpusWhenAsked) {
  const char* dir = std::getenv("THX_VRPN_FUZZ_WRITE_SEEDS");
  if (!dir) GTEST_SKIP() << "set THX_VRPN_FUZZ_WRITE_SEEDS=<dir> to write the seed corpus";
  const std::vector<Bytes> all = seeds();
  for (std::size_t i = 0; i < all.size(); ++i) {
    const std::string path = std::string(dir) + "/seed" + std::to_string(i);
    std::FILE* f = std::fopen(path.c_str(), "wb");
    ASSERT_TRUE(f) << path;
    EXPECT_EQ(std::fwrite(all[i].data(), 1, all[i].size(), f), all[i].size());
    std::fclose(f);
  }
}

TEST(FuzzDecoder, SeedsHoldTheInvariants) {
  for (const Bytes& s : seeds()) {
    const auto failure = fuzz::fuzzDecoderOnce(s);
    EXPECT_FALSE(failure) << *failure;
  }
}

TEST(FuzzDecoder, EveryMessageTypeSeedIsDeliveredWhole) {
  // Guards the seed's value: if it stopped reaching the typed decoders, the fuzz run would too.
  const Bytes s = everyMessageType();
  const fuzz::Run run = fuzz::runEndpoint(std::span(s).subspan(1), 0);
  ASSERT_FALSE(run.failure);
  ASSERT_EQ(run.events.size(), 1u + 22u + 1u);  // connected, 22 messages, the end of input
  EXPECT_EQ(run.events.back(), "dropped peer closed");
}

TEST(FuzzDecoder, ShortRun) {
  const std::vector<Bytes> pool = seeds();
  thx::fuzz::runMutated(
      "vrpn decoder", pool, [&](Bytes& b, Rng& rng) { mutate(b, rng, pool); }, &fuzz::fuzzDecoderOnce,
      "THX_VRPN_FUZZ_ITERATIONS", 4000);
}

}  // namespace test_fuzz_decoder
