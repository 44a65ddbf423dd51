#include "thx_client/logged_devices.hpp"

#include "base/error.hpp"
#include "thx_client/devices.hpp"
#include "thx_msgs/log_reader.hpp"

namespace thx::client {

LoggedDevice loggedDevice(const std::string& log_path, int device) {
  thx_msgs::hello_t widest{};  // the hello naming the most devices (none read: names nothing)
  std::size_t most = 0;
  bool any = false;
  thx_msgs::forEachLogMessage<thx_msgs::hello_t>(log_path, thx_msgs::kChannelHello,
                                                  [&](const thx_msgs::hello_t& h, const thx_msgs::LogPosition&) {
                                                    const std::size_t n = deviceNames(h).size();
                                                    if (any && n <= most) return;
                                                    widest = h;
                                                    most = n;
                                                    any = true;
                                                  });
  if (std::string problem = deviceProblem(widest, device); !problem.empty())
    throw Error(Error::Kind::Config, log_path + ": " + problem);
  return LoggedDevice{most <= 1, device};
}

}  // namespace thx::client
