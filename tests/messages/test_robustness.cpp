// Fingerprints, and decoding bad bytes: truncated buffers, wrong fingerprints, corrupt string
// lengths and array counts, random bit flips. Decoders must fail (< 0) and never read past the
// buffer (the buffers are exactly sized heap copies, so ASan sees any overrun).
#include <gtest/gtest.h>

#include <cstring>
#include <limits>
#include <random>
#include <set>
#include <tuple>

#include "message_fixtures.hpp"

namespace test_robustness {

using namespace thx_test;

namespace {

// One encoded example of every type, with a decoder that reports the decode() result.
struct Example {
  const char* name;
  std::int64_t hash;
  std::vector<std::uint8_t> bytes;
  int (*decode_as)(const std::vector<std::uint8_t>&);  // raw generated decode()
  int (*try_decode_as)(const std::vector<std::uint8_t>&);
};

template <class T>
int raw_decode(const std::vector<std::uint8_t>& b) {
  T m{};
  return m.decode(b.data(), 0, int(b.size()));
}
template <class T>
int safe_decode(const std::vector<std::uint8_t>& b) {
  T m{};
  return thx_msgs::try_decode(b.data(), b.size(), m);
}
template <class T>
Example example(const T& m) {
  return {T::getTypeName(), T::getHash(), encode(m), &raw_decode<T>, &safe_decode<T>};
}

std::vector<Example> all_examples() {
  return {example(make_device_state(1)),    example(make_contact(1)),          example(make_contact_batch(1, 3)),
          example(make_servo_stats(1)),     example(make_subscribe_request(1)), example(make_subscribe_reply(1)),
          example(make_heartbeat(1)),       example(make_hello(1)),            example(make_client_force(1)),
          example(make_server_command(1)),  example(make_server_command_reply(1))};
}

void put_i32(std::vector<std::uint8_t>& b, std::size_t offset, std::int32_t v) {
  const auto u = static_cast<std::uint32_t>(v);
  b.at(offset + 0) = std::uint8_t(u >> 24);
  b.at(offset + 1) = std::uint8_t(u >> 16);
  b.at(offset + 2) = std::uint8_t(u >> 8);
  b.at(offset + 3) = std::uint8_t(u);
}

}  // namespace

TEST(MessagesFingerprint, AllTypesDiffer) {
  std::set<std::int64_t> hashes;
  const auto ex = all_examples();
  for (const Example& e : ex) hashes.insert(e.hash);
  EXPECT_EQ(hashes.size(), ex.size());
}

// The fingerprints quoted in docs/messages.md: they change exactly when the wire format does.
TEST(MessagesFingerprint, PinnedValues) {
  const auto ex = all_examples();
  const std::vector<std::pair<std::string, std::uint64_t>> pinned = {
      {"device_state_t", 0x122ce6e3eda5b0f9ULL},      {"contact_t", 0x316657aa8ac8e93dULL},
      {"contact_batch_t", 0x8b52f3d70e560452ULL},     {"servo_stats_t", 0xe527119b05a1585cULL},
      {"subscribe_request_t", 0x5ca4f42b58b94e48ULL}, {"subscribe_reply_t", 0x84b15781bc5adcabULL},
      {"heartbeat_t", 0xc14aeafbbe46aeb3ULL},         {"hello_t", 0x7dafe74939a5488bULL},
      {"client_force_t", 0x987d99386980a8ffULL},      {"server_command_t", 0x110ed9ef106c0d74ULL},
      {"server_command_reply_t", 0xd86c7c73472596b0ULL}};
  ASSERT_EQ(pinned.size(), ex.size());
  for (std::size_t i = 0; i < ex.size(); ++i) {
    EXPECT_EQ(pinned[i].first, ex[i].name);
    EXPECT_EQ(pinned[i].second, static_cast<std::uint64_t>(ex[i].hash))
        << ex[i].name << " fingerprint 0x" << std::hex << static_cast<std::uint64_t>(ex[i].hash);
  }
}

TEST(MessagesFingerprint, DecodingAsAnotherTypeFails) {
  const auto ex = all_examples();
  for (const Example& from : ex) {
    for (const Example& as : ex) {
      const int expected = (&from == &as) ? int(from.bytes.size()) : -1;
      EXPECT_EQ(as.decode_as(from.bytes), expected) << from.name << " decoded as " << as.name;
      EXPECT_EQ(as.try_decode_as(from.bytes), expected) << from.name << " decoded as " << as.name;
    }
  }
}

TEST(MessagesFingerprint, AnyFlippedFingerprintBitFails) {
  for (const Example& e : all_examples()) {
    for (int bit = 0; bit < 64; ++bit) {
      std::vector<std::uint8_t> b = e.bytes;
      b[std::size_t(bit / 8)] ^= std::uint8_t(1u << (bit % 8));
      EXPECT_LT(e.decode_as(b), 0) << e.name << " bit " << bit;
    }
  }
}

TEST(MessagesDecode, EveryTruncationFails) {
  for (const Example& e : all_examples()) {
    for (std::size_t len = 0; len < e.bytes.size(); ++len) {
      const std::vector<std::uint8_t> b(e.bytes.begin(), e.bytes.begin() + std::ptrdiff_t(len));
      EXPECT_LT(e.decode_as(b), 0) << e.name << " truncated to " << len;
      EXPECT_LT(e.try_decode_as(b), 0) << e.name << " truncated to " << len;
    }
    // Trailing bytes are ignored: decode reports what it consumed.
    std::vector<std::uint8_t> longer = e.bytes;
    longer.resize(longer.size() + 5, 0xAB);
    EXPECT_EQ(e.decode_as(longer), int(e.bytes.size())) << e.name;
  }
}

TEST(MessagesDecode, NullOrHugeSizeIsRefused) {
  thx_msgs::heartbeat_t hb{};
  EXPECT_EQ(thx_msgs::try_decode(nullptr, 10, hb), -1);
  const std::uint8_t byte = 0;
  EXPECT_EQ(thx_msgs::try_decode(&byte, std::size_t(1) << 40, hb), -1);
  thx_msgs::contact_batch_t b{};
  EXPECT_EQ(thx_msgs::try_decode(nullptr, 100, b), -1);
}

// A corrupt string length. The generated decoder checks only "length > bytes left": a length
// <= 0 reaches std::string::assign(p, size_t(length - 1)) and throws, and INT32_MIN wraps to
// INT32_MAX and reads 2 GiB past the buffer. try_decode checks every string length first.
namespace {
template <class T>
void check_every_string_length_guarded(const T& msg) {
  SCOPED_TRACE(T::getTypeName());
  const std::vector<std::uint8_t> good = encode(msg);
  const auto& segments = thx_msgs::detail::string_layout<T>::segments;
  // The layout spans exactly the encoding (so its offsets are the encoder's).
  ASSERT_EQ(thx_msgs::detail::layout_extent(good.data(), good.size(), segments), std::ptrdiff_t(good.size()));
  std::size_t pos = 8;
  int strings = 0;
  for (int seg : segments) {
    if (seg != thx_msgs::detail::kString) {
      pos += std::size_t(seg);
      continue;
    }
    ++strings;
    const std::uint32_t len = (std::uint32_t{good[pos]} << 24) | (std::uint32_t{good[pos + 1]} << 16) |
                              (std::uint32_t{good[pos + 2]} << 8) | std::uint32_t{good[pos + 3]};
    ASSERT_GE(len, 1u);
    ASSERT_EQ(good[pos + 4 + len - 1], 0) << "string at " << pos << " is not NUL-terminated";
    for (std::int64_t bad : {0LL, -1LL, -100LL, (long long)std::numeric_limits<std::int32_t>::min(),
                             (long long)std::numeric_limits<std::int32_t>::max(), (long long)len + 1000,
                             (long long)good.size()}) {
      std::vector<std::uint8_t> b = good;
      put_i32(b, pos, std::int32_t(bad));
      T out{};
      int n = 0;
      EXPECT_NO_THROW(n = thx_msgs::try_decode(b.data(), b.size(), out)) << "string " << strings << " len " << bad;
      EXPECT_EQ(n, -1) << "string " << strings << " len " << bad;
    }
    // A string without its terminating NUL is refused too.
    std::vector<std::uint8_t> b = good;
    b[pos + 4 + len - 1] = 'x';
    T out{};
    EXPECT_EQ(thx_msgs::try_decode(b.data(), b.size(), out), -1) << "string " << strings << " without NUL";
    pos += 4 + len;
  }
  EXPECT_GT(strings, 0);
}
}  // namespace

TEST(MessagesDecode, CorruptStringLengthsFailWithoutThrowing) {
  check_every_string_length_guarded(make_subscribe_request(1));
  check_every_string_length_guarded(make_subscribe_reply(1));
  check_every_string_length_guarded(make_heartbeat(1));
  check_every_string_length_guarded(make_hello(1));
  check_every_string_length_guarded(make_client_force(1));
  check_every_string_length_guarded(make_server_command(1));
  check_every_string_length_guarded(make_server_command_reply(1));
  thx_msgs::server_command_t reset = make_server_command(1);
  reset.argument.clear();  // ACTION_RESET_FAULTS: no operand
  check_every_string_length_guarded(reset);
  // Empty strings are valid (length 1: just the NUL).
  thx_msgs::subscribe_reply_t refused = make_subscribe_reply(1);
  refused.channel.clear();
  refused.reason.clear();
  check_every_string_length_guarded(refused);
}

// Why try_decode exists: the raw generated decoder throws on a zero string length.
TEST(MessagesDecode, RawDecodeThrowsOnZeroStringLength) {
  std::vector<std::uint8_t> b = encode(make_subscribe_request(1));
  put_i32(b, 8 + 8 + 8, 0);  // client_id length: after fingerprint, utime, seq
  thx_msgs::subscribe_request_t out{};
  EXPECT_ANY_THROW(out.decode(b.data(), 0, int(b.size())));
}

// A corrupt sample count: try_decode rejects it before the decoder's vector::resize(count)
// (which for INT32_MAX would ask for ~700 GB).
TEST(MessagesDecode, CorruptBatchCountFailsBeforeAllocating) {
  const thx_msgs::contact_batch_t batch = make_contact_batch(2, 2);
  const std::vector<std::uint8_t> good = encode(batch);
  for (std::int32_t bad : {-1, 3, 1000, std::numeric_limits<std::int32_t>::max(),
                           std::numeric_limits<std::int32_t>::min()}) {
    std::vector<std::uint8_t> b = good;
    put_i32(b, thx_msgs::kBatchCountOffset, bad);
    thx_msgs::contact_batch_t out{};
    EXPECT_EQ(thx_msgs::try_decode(b.data(), b.size(), out), -1) << bad;
    EXPECT_EQ(thx_msgs::try_decode<thx_msgs::contact_batch_t>(b.data(), b.size(), out), -1) << bad;
  }
  // Fewer than encoded is a valid, shorter batch followed by ignored bytes.
  std::vector<std::uint8_t> b = good;
  put_i32(b, thx_msgs::kBatchCountOffset, 1);
  thx_msgs::contact_batch_t out{};
  EXPECT_EQ(thx_msgs::try_decode(b.data(), b.size(), out), int(thx_msgs::contact_batch_encoded_size(1)));
  ASSERT_EQ(out.samples.size(), 1u);
  expect_eq(out.samples[0], batch.samples[0]);
}

// Deterministic bit flips after the fingerprint: decoding may succeed (the bytes are still a
// valid message) or fail, but never throws, crashes or reads out of bounds.
TEST(MessagesDecode, RandomBitFlipsNeverCrash) {
  std::mt19937 rng(12345);
  for (const Example& e : all_examples()) {
    std::uniform_int_distribution<std::size_t> pos(8, e.bytes.size() - 1);
    std::uniform_int_distribution<int> bit(0, 7), nflips(1, 4);
    int ok = 0;
    for (int iter = 0; iter < 500; ++iter) {
      std::vector<std::uint8_t> b = e.bytes;
      for (int f = nflips(rng); f > 0; --f) b[pos(rng)] ^= std::uint8_t(1u << bit(rng));
      int n = 0;
      EXPECT_NO_THROW(n = e.try_decode_as(b)) << e.name;
      EXPECT_LE(n, int(b.size()));
      ok += n > 0;
    }
    EXPECT_GT(ok, 0) << e.name;  // flips in plain numbers decode fine
  }
}

}  // namespace test_robustness
