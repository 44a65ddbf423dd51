#include "server/server_commands.hpp"

#include <thx_msgs/protocol.hpp>

namespace thx::srv {

namespace {
using Cmd = thx_msgs::server_command_t;
}  // namespace

ServerCommands::ServerCommands(rt::LatestSlot<FaultReset>* reset_slot, std::int64_t server_instance)
    : reset_slot_(reset_slot), server_instance_(server_instance) {
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
  if (cmd.action != Cmd::ACTION_RESET_FAULTS) {
    return refuse(reply, "unknown action " + std::to_string(cmd.action) + ": expected 1 (reset faults)");
  }
  if (!cmd.argument.empty()) {
    return refuse(reply, "ACTION_RESET_FAULTS takes no argument, got " + std::to_string(cmd.argument.size()) +
                             " characters");
  }
  if (reset_slot_ == nullptr) return refuse(reply, "this server has no servo to reset");
  if (pending_.size() >= kMaxPending) {
    return refuse(reply, "too many commands waiting for the servo (" + std::to_string(kMaxPending) + ")");
  }
  reset_slot_->write(FaultReset{++reset_seq_});
  reply.accepted = true;
  pending_.push_back({reply, reset_seq_});
  return std::nullopt;
}

void ServerCommands::onRecord(const TickRecord& r, std::vector<thx_msgs::server_command_reply_t>& done) {
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
