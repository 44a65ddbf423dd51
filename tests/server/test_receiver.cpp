// Client forces entering hapticd: per-sender table rules, and the receiver thread end to end over
// an in-process LCM (memq://), including bytes that are not a client_force_t at all.
#include <gtest/gtest.h>

#include <chrono>
#include <lcm/lcm-cpp.hpp>
#include <thread>
#include <thx_msgs/client_force_t.hpp>
#include <thx_msgs/protocol.hpp>

#include "server/client_force_table.hpp"
#include "base/error.hpp"
#include "server/receiver.hpp"

namespace test_receiver {

using namespace thx;

namespace {
thx_msgs::client_force_t force(const std::string& id, const std::string& source, std::int64_t seq, double fx) {
  thx_msgs::client_force_t m{};
  m.client_id = id;
  m.source = source;
  m.seq = seq;
  m.f_world[0] = fx;
  return m;
}
constexpr std::int64_t kMs = 1'000'000;

// Waits up to 20 s for `slot` to hold a force whose x is `fx` (the receiver thread writes it; on
// a loaded machine that thread can wait for a CPU for much of a second).
bool slotReceives(rt::LatestSlot<srv::ClientForce>& slot, double fx) {
  srv::ClientForce got;
  std::uint32_t seq = 0;
  for (int k = 0; k < 4000; ++k) {
    if (slot.readIfNewer(got, seq) && got.force_world_n[0] == fx) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return false;
}
}  // namespace

TEST(ClientForceTable, KeepsTheLatestPerSenderAndSums) {
  srv::ClientForceTable t(7.9, 50 * kMs);
  EXPECT_TRUE(t.accept(force("physics", "sphere1", 1, 0.5), 0));
  EXPECT_TRUE(t.accept(force("physics", "sphere2", 1, 0.25), 0));
  EXPECT_TRUE(t.accept(force("physics", "sphere1", 2, 1.0), 1 * kMs));  // replaces 0.5
  EXPECT_NEAR(t.sum(2 * kMs).x(), 1.25, 1e-12);
  EXPECT_FALSE(t.accept(force("physics", "sphere1", 2, 3.0), 3 * kMs));  // not newer
  EXPECT_EQ(t.counters().stale_seq, 1u);
  EXPECT_NEAR(t.sum(40 * kMs).x(), 1.25, 1e-12);
  EXPECT_NEAR(t.sum(50 * kMs).x(), 1.0, 1e-12);  // sphere2 expired (received at 0)
  EXPECT_NEAR(t.sum(60 * kMs).x(), 0.0, 1e-12);
  EXPECT_EQ(t.liveEntries(), 0);
}

// Protocol 6 (several devices): a table sums the forces for its own device only.
TEST(ClientForceTable, AForceForAnotherDeviceIsRefusedAndCounted) {
  srv::ClientForceTable first(7.9, 50 * kMs);  // device 0, as hapticd's one device
  thx_msgs::client_force_t m = force("physics", "pen", 1, 0.5);
  m.device = 1;
  EXPECT_FALSE(first.accept(m, 0));
  EXPECT_EQ(first.counters().other_device, 1u);
  EXPECT_EQ(first.liveEntries(), 0);
  srv::ClientForceTable second(7.9, 50 * kMs, /*device=*/1);
  EXPECT_TRUE(second.accept(m, 0));
  EXPECT_NEAR(second.sum(1 * kMs).x(), 0.5, 1e-12);
}

TEST(ClientForceTable, RefusesBadInputAndBoundsItself) {
  srv::ClientForceTable t(7.9, 50 * kMs);
  EXPECT_FALSE(t.accept(force("physics", "x", 1, 8.5), 0));                    // above the peak force
  EXPECT_FALSE(t.accept(force("physics", "x", 1, std::nan("")), 0));           // not finite
  EXPECT_FALSE(t.accept(force("bad id with spaces", "x", 1, 0.1), 0));         // protocol id rules
  EXPECT_FALSE(t.accept(force("physics", std::string(200, 'a'), 1, 0.1), 0));  // tag too long
  EXPECT_EQ(t.counters().bad_values, 2u);
  EXPECT_EQ(t.counters().bad_ids, 2u);
  for (int k = 0; k < srv::ClientForceTable::kMaxEntries; ++k) {
    EXPECT_TRUE(t.accept(force("c" + std::to_string(k), "s", 1, 0.01), 0));
  }
  EXPECT_FALSE(t.accept(force("one_more", "s", 1, 0.01), 0));
  EXPECT_EQ(t.counters().table_full, 1u);
  thx_msgs::client_force_t pinned = force("pin", "s", 1, 0.1);
  pinned.timeout_us = 3'600'000'000;  // an hour: capped at 1 s
  t.sum(100 * kMs);                   // frees the table
  EXPECT_TRUE(t.accept(pinned, 0));
  EXPECT_NEAR(t.sum(999 * kMs).x(), 0.1, 1e-12);
  EXPECT_NEAR(t.sum(1000 * kMs).x(), 0.0, 1e-12);
}

TEST(Receiver, ForcesOverLcmReachTheServoSlotAndGarbageIsCounted) {
  lcm::LCM lcm("memq://");
  ASSERT_TRUE(lcm.good());
  rt::LatestSlot<srv::ClientForce> slot;
  srv::Receiver receiver(lcm, slot, 7.9);
  receiver.start();
  const std::string garbage = "definitely not a client_force_t";
  lcm.publish(thx_msgs::kChannelClientForce, garbage.data(), unsigned(garbage.size()));
  thx_msgs::client_force_t m = force("physics", "ball", 1, 0.75);
  lcm.publish(thx_msgs::kChannelClientForce, &m);
  const bool seen = slotReceives(slot, 0.75);
  receiver.stop();
  EXPECT_TRUE(seen);
  EXPECT_EQ(receiver.undecodable(), 1u);
  EXPECT_EQ(receiver.counters().accepted, 1u);
}

// Several devices (issue 30): each client force reaches the slot of the device it names, and
// only that one; a device the server does not have is refused and counted.
TEST(Receiver, EachForceReachesTheDeviceItNames) {
  lcm::LCM lcm("memq://");
  ASSERT_TRUE(lcm.good());
  rt::LatestSlot<srv::ClientForce> left, right;
  srv::Receiver receiver(lcm, {{&left, 7.9}, {&right, 3.3}});
  receiver.start();
  thx_msgs::client_force_t to_right = force("physics", "box", 1, 0.5);
  to_right.device = 1;
  lcm.publish(thx_msgs::kChannelClientForce, &to_right);
  thx_msgs::client_force_t too_strong_for_right = force("physics", "box", 2, 4.0);  // above right's 3.3 N
  too_strong_for_right.device = 1;
  lcm.publish(thx_msgs::kChannelClientForce, &too_strong_for_right);
  thx_msgs::client_force_t nowhere = force("physics", "ghost", 1, 0.25);
  nowhere.device = 2;
  lcm.publish(thx_msgs::kChannelClientForce, &nowhere);
  const bool seen = slotReceives(right, 0.5);
  for (int k = 0; k < 4000 && receiver.counters().other_device + receiver.counters().bad_values < 2; ++k)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  receiver.stop();
  EXPECT_TRUE(seen);
  std::uint32_t left_seq = 0;
  srv::ClientForce left_got;
  EXPECT_FALSE(left.readIfNewer(left_got, left_seq)) << "nothing was written to the left device's slot";
  EXPECT_EQ(receiver.counters().accepted, 1u);
  EXPECT_EQ(receiver.counters().bad_values, 1u);    // right's own peak force applies to right
  EXPECT_EQ(receiver.counters().other_device, 1u);  // device 2 of two
  EXPECT_THROW(srv::Receiver(lcm, std::vector<srv::ForcedDevice>{}), thx::Error);
}

}  // namespace test_receiver
