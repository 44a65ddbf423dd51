#include "thx_client/devices.hpp"

namespace thx::client {

std::vector<std::string> deviceNames(const thx_msgs::hello_t& hello) {
  std::vector<std::string> names;
  const std::string& all = hello.device_names;
  if (all.empty()) return names;
  for (std::size_t start = 0;;) {
    const std::size_t comma = all.find(',', start);
    names.push_back(all.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
    if (comma == std::string::npos) return names;
    start = comma + 1;
  }
}

std::string deviceProblem(const thx_msgs::hello_t& hello, int device) {
  const std::vector<std::string> names = deviceNames(hello);
  const int count = names.empty() ? 1 : int(names.size());
  if (device >= 0 && device < count) return "";
  const std::string server = hello.server_name.empty() ? std::string("hapticd") : hello.server_name;
  std::string listed;
  for (std::size_t i = 0; i < names.size(); ++i) listed += (i ? ", " : "") + std::to_string(i) + " " + names[i];
  if (names.empty()) listed = "0 (unnamed)";
  return "device " + std::to_string(device) + " is not one of " + server + "'s " + std::to_string(count) +
         (count == 1 ? " device: " : " devices: ") + listed + " (hello_t.device_names)";
}

}  // namespace thx::client
