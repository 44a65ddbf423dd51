#pragma once
// The vocabulary of server commands (server_command_t, docs/messages.md §5.10) as the kit speaks
// it: what each action is called in messages, which hello_t.protocol_version first answers it,
// the check of an argument before it goes out, and the error a refusal becomes. Client sends
// (Client::sendCommand); ClientApp waits for the reply (ClientApp::command, resetFaults, loadScene).
#include <cstdint>
#include <string>
#include <string_view>

#include <thx_msgs/server_command_reply_t.hpp>

#include "base/error.hpp"

namespace thx::client {

// "reset faults", "load scene 'vvalley'", "action 7 ('x')": for messages and errors.
std::string describeCommand(std::int32_t action, std::string_view argument);

// The hello_t.protocol_version from which hapticd answers `action` (2: reset, 3: load scene); 0
// for actions the kit does not know (the server decides: it refuses unknown ones).
int protocolVersionFor(std::int32_t action);

// "" when `argument` may go out with `action`, else why not: an argument of kMaxTextLength (200)
// characters or more, or for ACTION_LOAD_SCENE a name that is not a scene name (isValidSceneName:
// a file stem, never a path). The server checks again; this catches mistakes before the network.
std::string commandArgumentProblem(std::int32_t action, std::string_view argument);
// Throws thx::Error (Config) "cannot send 'load scene 'x y'': invalid scene name ..." when
// commandArgumentProblem finds one (Client::sendCommand and ClientApp::command, before anything goes out).
void requireSendable(std::int32_t action, std::string_view argument);

// The server refused a command (reply.accepted false): what() names the command, the server and
// its reason, e.g. "hapticd@lab1 refused to load scene 'x': scenes/x.yaml:3:1: ...". Nothing
// changed on the server.
class CommandRefused : public thx::Error {
 public:
  CommandRefused(const thx_msgs::server_command_reply_t& reply, const std::string& what)
      : thx::Error(Kind::Config, what), reply_(reply) {}
  const thx_msgs::server_command_reply_t& reply() const { return reply_; }

 private:
  thx_msgs::server_command_reply_t reply_;
};

}  // namespace thx::client
