#pragma once
// Reading our messages back from a standard LCM log (`hapticd --record`, lcm-logger): the events
// of one channel, each decoded with try_decode (a log is a file from outside: lengths are checked,
// never trusted). Used by hapticd's replay and the physics client's pen paths.
//
//   thx_msgs::forEachLogMessage<thx_msgs::device_state_t>(path, "THX_DEVICE_STATE",
//       [&](const thx_msgs::device_state_t& m, const thx_msgs::LogPosition& at) { ... });
//
// Errors throw LogError, whose message names the file, the event and the expected type:
//   session.lcm: event 12 (THX_DEVICE_STATE): does not decode as device_state_t
#include <lcm/lcm-cpp.hpp>
#include <string>

#include "base/error.hpp"
#include "thx_msgs/protocol.hpp"

namespace thx_msgs {

struct LogPosition {
  std::string file;
  long event = 0;  // 1-based index among all events of the file
  std::string channel;
  std::int64_t timestamp_us = 0;
  // "FILE: event N (CHANNEL)", the prefix of every error about this event.
  std::string where() const { return file + ": event " + std::to_string(event) + " (" + channel + ")"; }
};

class LogError : public thx::Error {
 public:
  explicit LogError(const std::string& what) : thx::Error(Kind::Io, what) {}
};

// Calls fn(message, position) for every event on `channel`, in file order. Throws LogError when
// the file is not an LCM log or an event on the channel does not decode as M; what fn throws
// passes through.
template <class M, class Fn>
void forEachLogMessage(const std::string& path, const std::string& channel, Fn fn) {
  lcm::LogFile log(path, "r");
  if (!log.good()) throw LogError(path + ": cannot open as an LCM log file");
  long n = 0;
  while (const lcm::LogEvent* e = log.readNextEvent()) {
    ++n;
    if (e->channel != channel) continue;
    const LogPosition at{path, n, e->channel, e->timestamp};
    M m;
    if (e->datalen < 0 || try_decode(e->data, std::size_t(e->datalen), m) < 0)
      throw LogError(at.where() + ": does not decode as " + M::getTypeName() + " (wrong type or corrupt)");
    fn(static_cast<const M&>(m), at);
  }
}

}  // namespace thx_msgs
