// Handoff: one object in flight, the owner frees the replaced one only after the rt side is done.
#include <gtest/gtest.h>

#include <atomic>
#include <memory>
#include <thread>
#include <vector>

#include "rt/handoff.hpp"

namespace test_handoff {

using thx::rt::Handoff;
using State = Handoff<int>::State;

TEST(Handoff, OneObjectGoesThroughOfferTakeCompleteReclaim) {
  Handoff<int> h;
  int a = 1;
  EXPECT_EQ(h.take(), nullptr);  // nothing offered
  EXPECT_FALSE(h.reclaim());
  ASSERT_TRUE(h.offer(&a));
  EXPECT_EQ(h.state(), State::Offered);
  EXPECT_FALSE(h.reclaim());      // not done yet: the owner may free nothing
  EXPECT_EQ(h.take(), &a);
  EXPECT_EQ(h.take(), nullptr);   // taken once
  EXPECT_FALSE(h.reclaim());      // taken but not completed: still in the rt thread's hands
  h.complete();
  EXPECT_EQ(h.state(), State::Done);
  EXPECT_TRUE(h.reclaim());
  EXPECT_FALSE(h.reclaim());      // once
  EXPECT_EQ(h.state(), State::Idle);
}

TEST(Handoff, ASecondOfferWaitsUntilTheFirstIsReclaimed) {
  Handoff<int> h;
  int a = 1, b = 2;
  ASSERT_TRUE(h.offer(&a));
  EXPECT_FALSE(h.offer(&b));
  EXPECT_EQ(h.take(), &a);  // b did not replace a
  EXPECT_FALSE(h.offer(&b));
  h.complete();
  EXPECT_FALSE(h.offer(&b));  // done but not reclaimed
  ASSERT_TRUE(h.reclaim());
  EXPECT_TRUE(h.offer(&b));
  EXPECT_EQ(h.take(), &b);
}

TEST(Handoff, NullIsNeverOfferedAndCompleteWithoutTakeDoesNothing) {
  Handoff<int> h;
  EXPECT_FALSE(h.offer(nullptr));
  h.complete();
  EXPECT_EQ(h.state(), State::Idle);
}

// An owner thread offers 2000 objects one after another; the rt thread swaps each in and reads
// the one it replaced until the moment it completes. The owner frees the replaced object right
// after reclaim(): under ASan a read of a freed object would fail the test.
TEST(Handoff, TheReplacedObjectIsFreedOnlyAfterTheRtThreadIsDone) {
  struct Scene {
    std::vector<int> data;
  };
  Handoff<const Scene> h;
  constexpr int kSwaps = 2000;
  auto current = std::make_unique<Scene>(Scene{std::vector<int>(64, 0)});
  const Scene* rt_current = current.get();
  std::atomic<bool> stop{false};
  std::atomic<long> sum{0};
  std::atomic<int> swaps_seen{0};
  std::thread rt([&] {
    long local = 0;
    while (!stop.load(std::memory_order_relaxed)) {
      for (int v : rt_current->data) local += v;  // the rt thread uses its scene every "tick"
      if (const Scene* next = h.take()) {
        rt_current = next;
        h.complete();
        swaps_seen.fetch_add(1, std::memory_order_relaxed);
      }
    }
    sum.store(local);
  });
  for (int k = 1; k <= kSwaps; ++k) {
    auto next = std::make_unique<Scene>(Scene{std::vector<int>(64, k)});
    while (!h.offer(next.get())) std::this_thread::yield();
    while (!h.reclaim()) std::this_thread::yield();
    current = std::move(next);  // frees the replaced scene: the rt thread is done with it
  }
  stop.store(true);
  rt.join();
  EXPECT_EQ(swaps_seen.load(), kSwaps);
  EXPECT_EQ(rt_current, current.get());
  EXPECT_GE(sum.load(), 0);
}

}  // namespace test_handoff
