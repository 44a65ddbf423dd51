#include "server/server_commands.hpp"

#include <thx_msgs/protocol.hpp>

#include "scenes/scene_lookup.hpp"

namespace thx::srv {

namespace {
using Cmd = thx_msgs::server_command_t;
}  // namespace

ServerCommands::ServerCommands(std::vector<rt::LatestSlot<FaultReset>*> reset_slots, std::int64_t server_instance,
                               SceneLoads* scenes)
    : reset_slots_(std::move(reset_slots)), scenes_(scenes), server_instance_(server_instance) {
  pending_.reserve(kMaxPending);
}

thx_msgs::server_command_reply_t ServerCommands::refuse(thx_msgs::server_command_reply_t reply, std::string reason) {
  reply.accepted = false;
  reply.reason = std::move(reason);
  reply.tick = -1;
  return reply;
}

std::optional<thx_msgs::server_command_reply_t> ServerCommands::handle(const Cmd& cmd) {
  thx_msgs::server_command_reply_t reply{};
  reply.server_instance = server_instance_;
  reply.request_seq = cmd.seq;
  // Echo only a valid id: the reply's strings must stay short and printable.
  reply.client_id = thx_msgs::is_valid_client_id(cmd.client_id) ? cmd.client_id : "?";
  reply.action = cmd.action;
  reply.tick = -1;
  if (!thx_msgs::is_valid_client_id(cmd.client_id)) {
    return refuse(reply, "invalid client_id: expected 1 to 32 characters of [A-Za-z0-9_-]");
  }
  if (cmd.action == Cmd::ACTION_RESET_FAULTS) return resetFaults(std::move(reply), cmd);
  if (cmd.action == Cmd::ACTION_LOAD_SCENE) return loadScene(std::move(reply), cmd);
  return refuse(reply, "unknown action " + std::to_string(cmd.action) + ": expected 1 (reset faults) or 2 (load scene)");
}

std::optional<thx_msgs::server_command_reply_t> ServerCommands::resetFaults(thx_msgs::server_command_reply_t reply,
                                                                            const Cmd& cmd) {
  if (!cmd.argument.empty()) {
    return refuse(reply, "ACTION_RESET_FAULTS takes no argument, got " + std::to_string(cmd.argument.size()) +
                             " characters");
  }
  if (reset_slots_.empty()) return refuse(reply, "this server has no servo to reset");
  if (pending_.size() >= kMaxPending) {
    return refuse(reply, "too many commands waiting for the servo (" + std::to_string(kMaxPending) + ")");
  }
  ++reset_seq_;
  for (rt::LatestSlot<FaultReset>* slot : reset_slots_) slot->write(FaultReset{reset_seq_});
  reply.accepted = true;
  pending_.push_back({reply, reset_seq_});
  return std::nullopt;
}

std::optional<thx_msgs::server_command_reply_t> ServerCommands::loadScene(thx_msgs::server_command_reply_t reply,
                                                                          const Cmd& cmd) {
  if (scenes_ == nullptr) return refuse(reply, "this server cannot switch scenes");
  if (load_) {
    return refuse(reply, "a switch to scene '" + load_->scene_name + "' is under way (client " +
                             load_->reply.client_id + "); ask again once it is answered");
  }
  if (cmd.argument.empty()) return refuse(reply, "ACTION_LOAD_SCENE needs the scene's name as its argument");
  // Checked before it is echoed anywhere: the argument is bytes from the network.
  if (!scene::isValidSceneName(cmd.argument)) {
    return refuse(reply, "invalid scene name (" + std::to_string(cmd.argument.size()) +
                             " characters): expected 1 to 100 characters of [A-Za-z0-9_.-], not starting with '.' "
                             "(a scene file's name without .yaml)");
  }
  if (std::optional<std::string> why = scenes_->begin(cmd.argument)) return refuse(reply, std::move(*why));
  load_ = PendingLoad{reply, cmd.argument, std::nullopt};
  return std::nullopt;
}

void ServerCommands::pollLoads(std::vector<thx_msgs::server_command_reply_t>& done) {
  if (!load_ || load_->loaded) return;
  std::optional<SceneLoads::Outcome> outcome = scenes_->poll();
  if (!outcome) return;
  if (!outcome->ok) {
    done.push_back(refuse(load_->reply, std::move(outcome->error)));
    load_.reset();
    return;
  }
  load_->loaded = std::move(outcome);
}

std::optional<ServerCommands::SceneChange> ServerCommands::takeSceneChange() {
  std::optional<SceneChange> c = std::move(scene_change_);
  scene_change_.reset();
  return c;
}

void ServerCommands::onRecord(const TickRecord& r, std::vector<thx_msgs::server_command_reply_t>& done) {
  if (load_ && load_->loaded && r.scene_swaps >= load_->loaded->swap) {
    thx_msgs::server_command_reply_t reply = std::move(load_->reply);
    reply.accepted = true;
    reply.tick = r.tick;
    done.push_back(std::move(reply));
    scene_change_ = SceneChange{std::move(load_->loaded->scene_name), load_->loaded->fingerprint, r.tick};
    load_.reset();
  }
  if (pending_.empty() || r.fault_resets == 0) return;
  std::size_t kept = 0;
  for (Pending& p : pending_) {
    // The servo reads only the newest reset: applying number n also covers every one before it.
    if (p.reset_seq <= r.fault_resets) {
      p.reply.tick = r.tick;
      done.push_back(std::move(p.reply));
    } else {
      if (&pending_[kept] != &p) pending_[kept] = std::move(p);  // a self-move would empty the strings
      ++kept;
    }
  }
  pending_.resize(kept);
}

}  // namespace thx::srv
