#pragma once
// Whose pens visual-client --replay-log draws (docs/visual.md "Several pens"): --device N's alone,
// else every device the session's hellos name, so a recording of a multi-device scene shows all
// its pens.
#include <optional>
#include <string>
#include <vector>

namespace thx::visual {

// The device indices for replayFrames(): {} (every state is the one pen) for a log whose hellos
// name one device or none, as thx_client/logged_devices.hpp takes such a log; {N} for `device`
// N of a multi-device log; else 0..n-1 for the n devices of the hello naming the most. Throws
// thx::Error (Config) naming the log, the index and the recorded names when the log has no device
// N; thx_msgs::LogError when the log does not read.
std::vector<int> replayedDevices(const std::string& log_path, std::optional<int> device);

}  // namespace thx::visual
