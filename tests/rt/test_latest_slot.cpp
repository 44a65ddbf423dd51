// LatestSlot: the newest complete value, never a torn one, never one already read.
#include <gtest/gtest.h>

#include <array>
#include <atomic>
#include <cstdint>
#include <thread>

#include "rt/latest_slot.hpp"

namespace test_latest_slot {

using thx::rt::LatestSlot;

namespace {
struct Wide {
  std::array<std::int64_t, 9> words{};  // 72 bytes: a torn copy would mix two writes
};
}  // namespace

TEST(LatestSlot, NothingToReadBeforeTheFirstWrite) {
  LatestSlot<int> slot;
  int out = 7;
  std::uint32_t seen = 0;
  EXPECT_FALSE(slot.readIfNewer(out, seen));
  EXPECT_EQ(out, 7);  // untouched: the caller keeps its previous value
  EXPECT_EQ(slot.sequence(), 0u);
}

TEST(LatestSlot, ReadsEachNewValueOnceAndOnlyTheNewest) {
  LatestSlot<double> slot;
  double out = 0.0;
  std::uint32_t seen = 0;
  slot.write(1.5);
  ASSERT_TRUE(slot.readIfNewer(out, seen));
  EXPECT_EQ(out, 1.5);
  EXPECT_FALSE(slot.readIfNewer(out, seen));  // already read
  slot.write(2.5);
  slot.write(3.5);  // latest value: 2.5 is overwritten, not queued
  ASSERT_TRUE(slot.readIfNewer(out, seen));
  EXPECT_EQ(out, 3.5);
  EXPECT_EQ(seen, slot.sequence());
  EXPECT_EQ(slot.sequence(), 6u);  // two per write
}

TEST(LatestSlot, ValuesWiderThanAWordArriveWhole) {
  LatestSlot<Wide> slot;
  Wide w;
  for (std::size_t k = 0; k < w.words.size(); ++k) w.words[k] = std::int64_t(k) * 11;
  slot.write(w);
  Wide out;
  std::uint32_t seen = 0;
  ASSERT_TRUE(slot.readIfNewer(out, seen));
  EXPECT_EQ(out.words, w.words);
}

// A writer and a reader racing: every value read is one that was written whole (all words equal),
// and the values read never go back in time. Whether a given read races a write depends on the
// scheduler, so the test asserts only what must hold for every interleaving.
TEST(LatestSlot, AConcurrentReaderNeverSeesATornOrOlderValue) {
  LatestSlot<Wide> slot;
  constexpr std::int64_t kWrites = 200'000;
  std::atomic<bool> done{false};
  std::thread writer([&] {
    Wide w;
    for (std::int64_t v = 1; v <= kWrites; ++v) {
      w.words.fill(v);
      slot.write(w);
    }
    done.store(true);
  });
  std::int64_t last = 0;
  std::uint32_t seen = 0;
  bool torn = false, backwards = false;
  Wide out;
  while (!done.load() || seen != slot.sequence()) {
    if (!slot.readIfNewer(out, seen)) continue;
    for (std::int64_t word : out.words) torn |= word != out.words[0];
    backwards |= out.words[0] < last;
    last = out.words[0];
  }
  writer.join();
  EXPECT_FALSE(torn);
  EXPECT_FALSE(backwards);
  EXPECT_EQ(last, kWrites);  // the final value is always read once the writer is done
}

}  // namespace test_latest_slot
