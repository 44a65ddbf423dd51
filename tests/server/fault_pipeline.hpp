#pragma once
// The servo in lock-step with a scripted device, its records turned into DEVICE_STATE messages
// and decimated for one subscriber exactly as hapticd's publisher does (tick_messages +
// SubscriptionTable), and client commands answered from the records (ServerCommands). No
// threads, no LCM, no clock: every tick is stepped by hand, so counts are exact.
#include <thx_msgs/protocol.hpp>

#include "server/server_commands.hpp"
#include "server/subscriptions.hpp"
#include "server/tick_messages.hpp"
#include "tests/clients/recording_sink.hpp"
#include "tests/server/servo_fixture.hpp"

namespace thx::test {

struct FaultPipeline {
  FaultPipeline(FakeDevice::Script script, double rate_hz) : rig(std::move(script)) {
    const auto reply = table.handleRequest(request("visual", "DEVICE_STATE", rate_hz), 0);
    EXPECT_TRUE(reply.accepted) << reply.reason;
  }

  // One servo tick, and everything the publisher does with its record.
  void step() {
    rig.servo().tick();
    srv::TickRecord r;
    while (rig.ring().pop(r)) {
      ticks.push_back(r);
      thx_msgs::device_state_t d{};
      thx_msgs::contact_t c{};
      srv::toDeviceState(r, true, d);
      table.onTick(d, c, r.deadline_ns / 1000, sink);
      commands.onRecord(r, replies);
    }
  }
  void run(int n) {
    for (int k = 0; k < n; ++k) step();
  }
  // The first message sent after servo tick `tick` (inclusive), or null.
  const thx_msgs::device_state_t* messageFrom(std::int64_t tick) const {
    for (const auto& m : sink.state_msgs) {
      if (m.tick >= tick) return &m;
    }
    return nullptr;
  }
  bool sentAt(std::int64_t tick) const {
    for (const auto& m : sink.state_msgs) {
      if (m.tick == tick) return true;
    }
    return false;
  }

  ServoRig rig;
  srv::SubscriptionTable table{srv::SubscriptionLimits{}};
  RecordingSink sink;
  srv::ServerCommands commands{&rig.servo().faultResetSlot(), 42};
  std::vector<thx_msgs::server_command_reply_t> replies;
  std::vector<srv::TickRecord> ticks;
};

inline thx_msgs::server_command_t resetCommand(std::int64_t seq, const std::string& id = "study") {
  thx_msgs::server_command_t c{};
  c.seq = seq;
  c.client_id = id;
  c.action = thx_msgs::server_command_t::ACTION_RESET_FAULTS;
  return c;
}

// A pen hovering 2 mm above the rig's surface: no contact, no force.
inline void hover(std::int64_t, dev::DeviceState& s) { s.p_world = Eigen::Vector3d(0.0, 0.0, 0.002); }

}  // namespace thx::test
