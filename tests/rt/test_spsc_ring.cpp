// SpscRing: first in, first out; a full ring drops the new record and counts it, never blocks.
#include <gtest/gtest.h>

#include <cstdint>
#include <thread>

#include "rt/spsc_ring.hpp"

namespace test_spsc_ring {

using thx::rt::SpscRing;

TEST(SpscRing, CapacityRoundsUpToAPowerOfTwo) {
  EXPECT_EQ(SpscRing<int>(1).capacity(), 1u);
  EXPECT_EQ(SpscRing<int>(5).capacity(), 8u);
  EXPECT_EQ(SpscRing<int>(1024).capacity(), 1024u);
}

TEST(SpscRing, PopsInTheOrderPushed) {
  SpscRing<int> ring(4);
  int out = 0;
  EXPECT_FALSE(ring.pop(out));
  for (int v = 0; v < 3; ++v) EXPECT_TRUE(ring.push(v));
  EXPECT_EQ(ring.size(), 3u);
  for (int v = 0; v < 3; ++v) {
    ASSERT_TRUE(ring.pop(out));
    EXPECT_EQ(out, v);
  }
  EXPECT_FALSE(ring.pop(out));
  EXPECT_EQ(ring.size(), 0u);
}

TEST(SpscRing, AFullRingDropsTheNewRecordAndCountsIt) {
  SpscRing<int> ring(4);
  for (int v = 0; v < 4; ++v) EXPECT_TRUE(ring.push(v));
  EXPECT_FALSE(ring.push(99));
  EXPECT_FALSE(ring.push(100));
  EXPECT_EQ(ring.dropped(), 2u);
  int out = -1;
  ASSERT_TRUE(ring.pop(out));
  EXPECT_EQ(out, 0);  // the old records stay; the new ones were dropped
  EXPECT_TRUE(ring.push(4));
  for (int v = 1; v <= 4; ++v) {
    ASSERT_TRUE(ring.pop(out));
    EXPECT_EQ(out, v);
  }
}

TEST(SpscRing, WrapsAroundManyTimes) {
  SpscRing<std::uint64_t> ring(8);
  std::uint64_t out = 0;
  for (std::uint64_t v = 0; v < 1000; ++v) {
    ASSERT_TRUE(ring.push(v));
    ASSERT_TRUE(ring.pop(out));
    ASSERT_EQ(out, v);
  }
  EXPECT_EQ(ring.dropped(), 0u);
}

// One producer and one consumer thread: every record either arrives, in order, or is counted as
// dropped. How many are dropped depends on the scheduler, so only the sum is asserted.
TEST(SpscRing, ConcurrentRecordsArriveInOrderOrAreCountedAsDropped) {
  SpscRing<std::uint64_t> ring(64);
  constexpr std::uint64_t kRecords = 200'000;
  std::thread producer([&] {
    for (std::uint64_t v = 1; v <= kRecords; ++v) ring.push(v);
  });
  std::uint64_t received = 0, last = 0, out = 0;
  bool in_order = true;
  auto drain = [&] {
    while (ring.pop(out)) {
      in_order &= out > last;
      last = out;
      ++received;
    }
  };
  while (received + ring.dropped() < kRecords && last < kRecords) drain();
  producer.join();
  drain();  // whatever arrived after the last check
  EXPECT_TRUE(in_order);
  EXPECT_EQ(received + ring.dropped(), kRecords);
}

}  // namespace test_spsc_ring
