#include "clients/visual/replay_devices.hpp"

#include <algorithm>
#include <thx_msgs/hello_t.hpp>
#include <thx_msgs/log_reader.hpp>
#include <thx_msgs/protocol.hpp>

#include "thx_client/devices.hpp"
#include "thx_client/logged_devices.hpp"

namespace thx::visual {

std::vector<int> replayedDevices(const std::string& log_path, std::optional<int> device) {
  if (device) {
    const client::LoggedDevice pen = client::loggedDevice(log_path, *device);
    return pen.every ? std::vector<int>{} : std::vector<int>{pen.device};
  }
  std::size_t most = 0;
  thx_msgs::forEachLogMessage<thx_msgs::hello_t>(
      log_path, thx_msgs::kChannelHello,
      [&](const thx_msgs::hello_t& h, const thx_msgs::LogPosition&) { most = std::max(most, client::deviceNames(h).size()); });
  std::vector<int> all;
  for (int i = 0; most > 1 && i < int(most); ++i) all.push_back(i);
  return all;
}

}  // namespace thx::visual
