#include "thx_client/commands.hpp"

#include <thx_msgs/protocol.hpp>

#include "thx_client/scene_check.hpp"

namespace thx::client {

namespace {
using Cmd = thx_msgs::server_command_t;
}  // namespace

std::string describeCommand(std::int32_t action, std::string_view argument) {
  switch (action) {
    case Cmd::ACTION_RESET_FAULTS:
      return "reset faults";
    case Cmd::ACTION_LOAD_SCENE:
      return "load scene '" + std::string(argument) + "'";
    default:
      return "action " + std::to_string(action) + " ('" + std::string(argument) + "')";
  }
}

int protocolVersionFor(std::int32_t action) {
  switch (action) {
    case Cmd::ACTION_RESET_FAULTS:
      return 2;
    case Cmd::ACTION_LOAD_SCENE:
      return 3;
    default:
      return 0;
  }
}

std::string commandArgumentProblem(std::int32_t action, std::string_view argument) {
  if (argument.size() >= thx_msgs::kMaxTextLength)
    return "a command argument of " + std::to_string(argument.size()) + " characters: expected fewer than " +
           std::to_string(thx_msgs::kMaxTextLength);
  if (action == Cmd::ACTION_LOAD_SCENE && !isValidSceneName(std::string(argument)))
    return "invalid scene name '" + std::string(argument) +
           "': expected 1 to 100 characters of [A-Za-z0-9_.-], not starting with '.' (a scene file's name "
           "without .yaml, found by hapticd in its scenes folder)";
  return {};
}

void requireSendable(std::int32_t action, std::string_view argument) {
  if (const std::string problem = commandArgumentProblem(action, argument); !problem.empty())
    throw thx::Error(thx::Error::Kind::Config, "cannot send '" + describeCommand(action, argument) + "': " + problem);
}

}  // namespace thx::client
