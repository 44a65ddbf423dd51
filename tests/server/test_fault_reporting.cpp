// Faults a client can see (docs/messages.md §5.1): the latched fault_code, the fault_mask and
// flags_seen a decimated DEVICE_STATE stream ORs over the ticks it skips, the client's reset
// command and its reply. The servo runs in lock-step with a scripted device and its records go
// through the publisher's own conversion and decimation (fault_pipeline.hpp): exact, no timing.
#include <gtest/gtest.h>

#include <lcm/lcm-cpp.hpp>
#include <limits>

#include "server/subscription_inbox.hpp"
#include "tests/server/fault_pipeline.hpp"

namespace test_fault_reporting {

using namespace thx;
using test::FaultPipeline;
using D = thx_msgs::device_state_t;

namespace {
constexpr std::int32_t bit(std::int32_t code) { return std::int32_t{1} << code; }
}  // namespace

TEST(FaultReporting, AOneTickFaultReachesA60HzSubscriber) {
  FaultPipeline p(
      [](std::int64_t tick, dev::DeviceState& s) {
        test::hover(tick, s);
        // A 4-tick gap over which the pen jumped 5 mm (the policy rides through gaps, not jumps):
        // the tick after the gap (514) raises the fault.
        if (tick == 510) s.timing.missed = 4;
        if (tick >= 510) s.p_world.z() += 0.005;
      },
      60.0);
  p.run(700);
  constexpr std::int64_t kFaultTick = 514;
  ASSERT_EQ(p.ticks[510].tick, kFaultTick);
  ASSERT_EQ(p.ticks[510].faults, std::uint32_t{srv::kFaultMissedTicks});
  ASSERT_FALSE(p.sentAt(kFaultTick)) << "the fault tick itself must be one the 60 Hz stream skips";

  const D* m = p.messageFrom(kFaultTick);
  ASSERT_NE(m, nullptr);
  EXPECT_EQ(m->fault_mask, bit(D::FAULT_MISSED_TICKS));
  EXPECT_TRUE(m->flags_seen & D::FLAG_FAULT);
  EXPECT_TRUE(m->flags_seen & D::FLAG_MISSED_TICK);
  EXPECT_FALSE(m->flags & D::FLAG_FAULT) << "flags describe the message's own tick only";
  EXPECT_EQ(m->fault_code, D::FAULT_MISSED_TICKS);

  // Later messages: the mask is per message, the code stays latched.
  for (const D& later : p.sink.state_msgs) {
    if (later.tick <= m->tick) continue;
    EXPECT_EQ(later.fault_mask, 0) << later.tick;
    EXPECT_FALSE(later.flags_seen & D::FLAG_FAULT) << later.tick;
    EXPECT_EQ(later.fault_code, D::FAULT_MISSED_TICKS) << later.tick;
  }
  // Before it: no fault at all.
  for (const D& earlier : p.sink.state_msgs) {
    if (earlier.tick >= kFaultTick) break;
    EXPECT_EQ(earlier.fault_code, D::FAULT_NONE);
    EXPECT_EQ(earlier.fault_mask, 0);
  }
}

TEST(FaultReporting, TheFirstFaultStaysLatchedUntilAClientResetsIt) {
  FaultPipeline p(
      [](std::int64_t tick, dev::DeviceState& s) {
        test::hover(tick, s);
        if (tick == 300) s.timing.missed = 25;                          // first: missed ticks (325)
        if (tick >= 400 && tick < 403) s.valid = false;                 // second: device I/O (402)
        if (tick >= 600 && tick < 603) s.p_world.z() = std::nan("");  // after the reset (602)
      },
      1000.0);
  p.run(450);
  ASSERT_FALSE(p.sink.state_msgs.empty());
  const D& before_reset = p.sink.state_msgs.back();
  EXPECT_EQ(before_reset.fault_code, D::FAULT_MISSED_TICKS) << "the first fault, not the latest";
  const D* io = p.messageFrom(402);  // the third invalid reading in a row
  ASSERT_NE(io, nullptr);
  EXPECT_EQ(io->tick, 402);
  EXPECT_EQ(io->fault_mask, bit(D::FAULT_DEVICE_IO));
  EXPECT_EQ(io->fault_code, D::FAULT_MISSED_TICKS);

  EXPECT_FALSE(p.commands.handle(test::resetCommand(7)).has_value()) << "answered once the servo applied it";
  EXPECT_TRUE(p.replies.empty());
  p.step();
  ASSERT_EQ(p.replies.size(), 1u);
  const auto& reply = p.replies[0];
  EXPECT_TRUE(reply.accepted);
  EXPECT_EQ(reply.reason, "");
  EXPECT_EQ(reply.request_seq, 7);
  EXPECT_EQ(reply.client_id, "study");
  EXPECT_EQ(reply.server_instance, 42);
  EXPECT_EQ(reply.tick, p.ticks.back().tick);
  EXPECT_EQ(p.sink.state_msgs.back().tick, reply.tick);
  EXPECT_EQ(p.sink.state_msgs.back().fault_code, D::FAULT_NONE) << "cleared from the reply's tick on";
  EXPECT_EQ(p.commands.pending(), 0u);

  p.run(250);
  for (const D& m : p.sink.state_msgs) {
    if (m.tick <= reply.tick) continue;
    EXPECT_EQ(m.fault_code, m.tick < 602 ? std::int32_t{D::FAULT_NONE} : std::int32_t{D::FAULT_DEVICE_IO}) << m.tick;
  }
}

TEST(FaultReporting, ResetsAreAnsweredEvenWhenRecordsAreLostAndBadCommandsAreRefused) {
  FaultPipeline p(test::hover, 1000.0);
  p.run(5);
  // Two resets before the servo runs: it reads only the newest, which covers both.
  EXPECT_FALSE(p.commands.handle(test::resetCommand(1)).has_value());
  EXPECT_FALSE(p.commands.handle(test::resetCommand(2)).has_value());
  p.rig.servo().tick();
  srv::TickRecord lost;
  ASSERT_TRUE(p.rig.ring().pop(lost));  // this record never reaches the publisher
  EXPECT_TRUE(p.replies.empty());
  p.step();  // a later record shows the resets applied
  ASSERT_EQ(p.replies.size(), 2u);
  EXPECT_EQ(p.replies[0].request_seq, 1);
  EXPECT_EQ(p.replies[1].request_seq, 2);
  EXPECT_EQ(p.replies[1].tick, lost.tick + 1);

  auto refused = [&](thx_msgs::server_command_t c) {
    const auto r = p.commands.handle(c);
    EXPECT_TRUE(r.has_value());
    if (!r) return std::string();
    EXPECT_FALSE(r->accepted);
    EXPECT_EQ(r->tick, -1);
    EXPECT_EQ(r->request_seq, c.seq);
    return r->reason;
  };
  EXPECT_NE(refused(test::resetCommand(3, "bad id!")).find("invalid client_id"), std::string::npos);
  auto unknown = test::resetCommand(4);
  unknown.action = 99;
  EXPECT_NE(refused(unknown).find("unknown action 99"), std::string::npos);
  auto with_argument = test::resetCommand(5);
  with_argument.argument = "scenes/default.yaml";
  EXPECT_NE(refused(with_argument).find("takes no argument"), std::string::npos);
  srv::ServerCommands no_servo(nullptr, 1);
  const auto r = no_servo.handle(test::resetCommand(6));
  ASSERT_TRUE(r.has_value());
  EXPECT_FALSE(r->accepted);
  EXPECT_EQ(p.commands.pending(), 0u);
}

// THX_COMMAND is a client -> server channel: its bytes are decoded with try_decode, and bytes
// that are not one whole server_command_t are counted and dropped, never crash the server.
TEST(FaultReporting, CommandBytesAreDecodedSafely) {
  lcm::LCM lcm("memq://");
  ASSERT_TRUE(lcm.good());
  srv::SubscriptionInbox inbox;
  inbox.attach(lcm);
  const std::string garbage = "definitely not a server_command_t";
  lcm.publish(thx_msgs::kChannelCommand, garbage.data(), unsigned(garbage.size()));
  std::vector<std::uint8_t> bytes(std::size_t(test::resetCommand(1).getEncodedSize()));
  test::resetCommand(1).encode(bytes.data(), 0, int(bytes.size()));
  lcm.publish(thx_msgs::kChannelCommand, bytes.data(), unsigned(bytes.size() - 3));  // truncated
  bytes[8 + 16 + 3] = 0xff;  // client_id length 0x000000ff: beyond the message
  lcm.publish(thx_msgs::kChannelCommand, bytes.data(), unsigned(bytes.size()));
  const auto good = test::resetCommand(2);
  lcm.publish(thx_msgs::kChannelCommand, &good);
  while (lcm.handleTimeout(0) > 0) {
  }
  srv::ControlMessages got;
  inbox.take(got);
  ASSERT_EQ(got.commands.size(), 1u);
  EXPECT_EQ(got.commands[0].msg.seq, 2);
  EXPECT_EQ(got.commands[0].msg.client_id, "study");
  EXPECT_EQ(inbox.undecodable(), 3u);
}

}  // namespace test_fault_reporting
