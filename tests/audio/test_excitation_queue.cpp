// The lock-free single-producer single-consumer queue of excitation events (clients/audio/
// excitation.hpp, rt::SpscRing): order, a full queue dropping and counting, front() without
// removing, wrap-around, and two threads handing over every event in order.
#include <gtest/gtest.h>

#include <thread>
#include <vector>

#include "clients/audio/synthesis/excitation.hpp"

namespace thx::audio::test_excitation_queue {
namespace {

ExcitationEvent event(std::int64_t t) {
  ExcitationEvent e;
  e.time_ns = t;
  e.node = int(t % 97);
  e.impulse[2] = double(t) * 0.5;
  return e;
}

TEST(ExcitationQueue, FirstInFirstOutWithFrontNotRemoving) {
  ExcitationQueue q(8);
  EXPECT_EQ(q.front(), nullptr);
  for (int t = 0; t < 5; ++t) ASSERT_TRUE(q.push(event(t)));
  ASSERT_NE(q.front(), nullptr);
  EXPECT_EQ(q.front()->time_ns, 0);
  EXPECT_EQ(q.front()->time_ns, 0);  // front() again: still there
  EXPECT_EQ(q.size(), 5u);
  ExcitationEvent e;
  for (int t = 0; t < 5; ++t) {
    ASSERT_TRUE(q.pop(e));
    EXPECT_EQ(e.time_ns, t);
    EXPECT_EQ(e.node, t % 97);
    EXPECT_EQ(e.impulse[2], t * 0.5);
  }
  EXPECT_FALSE(q.pop(e));
  EXPECT_EQ(q.front(), nullptr);
}

TEST(ExcitationQueue, FullQueueDropsTheNewEventAndCountsIt) {
  ExcitationQueue q(4);
  for (int t = 0; t < 4; ++t) ASSERT_TRUE(q.push(event(t)));
  EXPECT_FALSE(q.push(event(99)));
  EXPECT_FALSE(q.push(event(100)));
  EXPECT_EQ(q.dropped(), 2u);
  ExcitationEvent e;
  ASSERT_TRUE(q.pop(e));
  EXPECT_EQ(e.time_ns, 0);  // the oldest stays; the new ones were dropped
  EXPECT_TRUE(q.push(event(4)));
  for (int t = 1; t <= 4; ++t) {
    ASSERT_TRUE(q.pop(e));
    EXPECT_EQ(e.time_ns, t);
  }
}

TEST(ExcitationQueue, WrapsAroundManyTimes) {
  ExcitationQueue q(4);
  ExcitationEvent e;
  std::int64_t next_out = 0;
  for (std::int64_t t = 0; t < 1000; ++t) {
    ASSERT_TRUE(q.push(event(t)));
    if (t % 3 == 2) {
      while (q.pop(e)) EXPECT_EQ(e.time_ns, next_out++);
    }
  }
  while (q.pop(e)) EXPECT_EQ(e.time_ns, next_out++);
  EXPECT_EQ(next_out, 1000);
  EXPECT_EQ(q.dropped(), 0u);
}

TEST(ExcitationQueue, TwoThreadsHandOverEveryEventInOrder) {
  ExcitationQueue q(64);
  constexpr std::int64_t kEvents = 20000;
  std::thread producer([&] {
    for (std::int64_t t = 0; t < kEvents; ++t)
      while (!q.push(event(t))) std::this_thread::yield();  // the test's producer retries; the feed drops
  });
  std::vector<std::int64_t> got;
  got.reserve(kEvents);
  ExcitationEvent e;
  while (std::int64_t(got.size()) < kEvents) {
    if (const ExcitationEvent* f = q.front()) {
      const std::int64_t peeked = f->time_ns;
      ASSERT_TRUE(q.pop(e));
      ASSERT_EQ(e.time_ns, peeked);
      got.push_back(e.time_ns);
    } else {
      std::this_thread::yield();
    }
  }
  producer.join();
  for (std::int64_t t = 0; t < kEvents; ++t) ASSERT_EQ(got[std::size_t(t)], t);
  EXPECT_FALSE(q.pop(e));
}

}  // namespace
}  // namespace thx::audio::test_excitation_queue
