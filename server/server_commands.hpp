#pragma once
// Client commands (server_command_t on THX_COMMAND, docs/messages.md §5.10), on the publisher
// thread. Each command is checked; a refusal is answered at once. ACTION_RESET_FAULTS is handed
// to the servo through its latest-value slot (never a lock) and answered only when a tick record
// shows the servo applied it, so an accepted reply means the latch was cleared, and says at which
// tick. ACTION_LOAD_SCENE goes to the scene loader (scene_loads.hpp): a load that fails is
// refused with the loader's message; one that succeeds is answered when a tick record shows the
// servo rendering it (TickRecord::scene_swaps), and the new scene is then announced
// (takeSceneChange). One scene switch at a time. Pure bookkeeping: no LCM, no clock, no
// thread, so tests drive it with tick records and a fake loader.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <thx_msgs/server_command_reply_t.hpp>
#include <thx_msgs/server_command_t.hpp>

#include "rt/latest_slot.hpp"
#include "server/scene_loads.hpp"
#include "server/servo.hpp"
#include "server/tick_record.hpp"

namespace thx::srv {

class ServerCommands {
 public:
  // Resets waiting for the servo beyond this are refused (a client flooding a stalled servo).
  static constexpr std::size_t kMaxPending = 256;

  // reset_slots: every device's servo's (Servo::faultResetSlot()), device 0 first; this object
  // must be their only writer. A reset clears every device's latch (server_command_t names no
  // device) and is answered when device 0's record shows it applied: each servo applies it at
  // its next tick, and the group ticks them together. Empty: resets are refused (a server
  // without a servo to reset). scenes: null refuses switches.
  ServerCommands(std::vector<rt::LatestSlot<FaultReset>*> reset_slots, std::int64_t server_instance,
                 SceneLoads* scenes = nullptr);
  // One device's slot (null: resets refused).
  ServerCommands(rt::LatestSlot<FaultReset>* reset_slot, std::int64_t server_instance, SceneLoads* scenes = nullptr)
      : ServerCommands(reset_slot ? std::vector<rt::LatestSlot<FaultReset>*>{reset_slot}
                                  : std::vector<rt::LatestSlot<FaultReset>*>{},
                       server_instance, scenes) {}

  // The reply to send now (a refusal), or nothing when the answer waits for the servo.
  std::optional<thx_msgs::server_command_reply_t> handle(const thx_msgs::server_command_t& cmd);
  // Appends to `done` the replies of the scene loads that failed since the last call.
  void pollLoads(std::vector<thx_msgs::server_command_reply_t>& done);
  // Appends to `done` the replies of the commands this record shows applied.
  void onRecord(const TickRecord& r, std::vector<thx_msgs::server_command_reply_t>& done);
  std::size_t pending() const { return pending_.size() + (load_ ? 1 : 0); }

  // The scene the servo switched to, once per switch, after the record that shows it.
  struct SceneChange {
    std::string scene_name;
    std::uint64_t fingerprint = 0;
    std::int64_t tick = 0;  // first tick on the new surface
  };
  std::optional<SceneChange> takeSceneChange();

 private:
  struct Pending {
    thx_msgs::server_command_reply_t reply;
    std::uint32_t reset_seq = 0;
  };
  struct PendingLoad {
    thx_msgs::server_command_reply_t reply;
    std::string scene_name;
    std::optional<SceneLoads::Outcome> loaded;  // set once the loader handed it to the servo
  };
  thx_msgs::server_command_reply_t refuse(thx_msgs::server_command_reply_t reply, std::string reason);
  std::optional<thx_msgs::server_command_reply_t> resetFaults(thx_msgs::server_command_reply_t reply,
                                                               const thx_msgs::server_command_t& cmd);
  std::optional<thx_msgs::server_command_reply_t> loadScene(thx_msgs::server_command_reply_t reply,
                                                             const thx_msgs::server_command_t& cmd);

  std::vector<rt::LatestSlot<FaultReset>*> reset_slots_;
  SceneLoads* scenes_;
  std::optional<PendingLoad> load_;
  std::optional<SceneChange> scene_change_;
  std::int64_t server_instance_;
  std::uint32_t reset_seq_ = 0;
  std::vector<Pending> pending_;
};

}  // namespace thx::srv
