#pragma once
// Client commands (server_command_t on THX_COMMAND, docs/messages.md §5.10), on the publisher
// thread. Each command is checked; a refusal is answered at once. ACTION_RESET_FAULTS is handed
// to the servo through its latest-value slot (never a lock) and answered only when a tick record
// shows the servo applied it, so an accepted reply means the latch was cleared, and says at which
// tick. Pure bookkeeping: no LCM, no clock, so tests drive it with tick records.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <thx_msgs/server_command_reply_t.hpp>
#include <thx_msgs/server_command_t.hpp>

#include "rt/latest_slot.hpp"
#include "server/servo.hpp"
#include "server/tick_record.hpp"

namespace thx::srv {

class ServerCommands {
 public:
  // Resets waiting for the servo beyond this are refused (a client flooding a stalled servo).
  static constexpr std::size_t kMaxPending = 256;

  // reset_slot: the servo's (Servo::faultResetSlot()); this object must be its only writer.
  // Null: resets are refused (a server without a servo to reset).
  ServerCommands(rt::LatestSlot<FaultReset>* reset_slot, std::int64_t server_instance);

  // The reply to send now (a refusal), or nothing when the answer waits for the servo.
  std::optional<thx_msgs::server_command_reply_t> handle(const thx_msgs::server_command_t& cmd);
  // Appends to `done` the replies of the commands this record shows applied.
  void onRecord(const TickRecord& r, std::vector<thx_msgs::server_command_reply_t>& done);
  std::size_t pending() const { return pending_.size(); }

 private:
  struct Pending {
    thx_msgs::server_command_reply_t reply;
    std::uint32_t reset_seq = 0;
  };
  thx_msgs::server_command_reply_t refuse(thx_msgs::server_command_reply_t reply, std::string reason);

  rt::LatestSlot<FaultReset>* reset_slot_;
  std::int64_t server_instance_;
  std::uint32_t reset_seq_ = 0;
  std::vector<Pending> pending_;
};

}  // namespace thx::srv
