#pragma once
// Whose pen is a recorded session's device-tagged message (device_state_t, contact_t; protocol
// 6)? hapticd --record writes its hello, with device_names, before the first tick; a client that
// replays the log offline (physics-client, visual-client and audio-client --replay-log) takes the
// messages of the one device it follows, as the kit's Client does live (devices.hpp).
// A log whose hellos name one device, or that holds no hello, is that one device's: every message
// is taken whatever its `device` field holds, so such a log replays exactly as before. (The field
// cannot be trusted there: hapticd's session recorder as protocol 6 first shipped leaves it unset,
// server/session_log.cpp.)
#include <cstdint>
#include <string>

namespace thx::client {

struct LoggedDevice {
  bool every = true;  // a one-device log: every message is the pen's
  int device = 0;     // else only this index's
  bool takes(std::int32_t message_device) const { return every || message_device == device; }
};

// Which of the log's messages are device `device`'s, from the hello naming the most devices.
// Throws thx::Error (Config) naming the log, the index and the logged device names when the log
// has no such device (deviceProblem), thx_msgs::LogError when the log does not read.
LoggedDevice loggedDevice(const std::string& log_path, int device);

}  // namespace thx::client
