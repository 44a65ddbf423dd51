#pragma once
// Which of hapticd's devices a client follows (protocol 6, issue 30). A server with several
// devices sends each subscriber every device's messages on its one channel, each tagged with
// `device`, its index in hello_t.device_names ("Phantom0,Phantom1"). The kit's Client follows one
// index (ClientOptions::device, 0 by default): the others' messages are counted, not delivered,
// so a client written for one pen never sees two; a client that plays every pen asks for them all
// (ClientOptions::every_device). docs/clients.md §3.4.
#include <array>
#include <cstdint>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include <thx_msgs/device_state_t.hpp>
#include <thx_msgs/hello_t.hpp>

#include "scenes/scene.hpp"

namespace thx::client {

// A scene, and so hapticd, has at most this many devices; the kit's per-device tables are this
// long, so no message makes them grow.
inline constexpr int kMaxDevices = int(scene::kMaxSceneDevices);

// hello_t.device_names split at its commas, in index order ("" gives none).
std::vector<std::string> deviceNames(const thx_msgs::hello_t& hello);

// "" when `device` is one of the hello's devices, else why not, naming the index and the names:
//   "device 2 is not one of hapticd@pc's 2 devices: 0 Phantom0, 1 Phantom1 (hello_t.device_names)"
// A hello that names no device (a test double, a server before protocol 6) has device 0 only.
std::string deviceProblem(const thx_msgs::hello_t& hello, int device);

// The newest device_state_t of every device index 0..kMaxDevices-1, whichever device a client
// follows: for a client that draws or couples several pens. Fixed size: storing copies a
// message into its slot and allocates nothing. Any thread (a mutex, as LatestValue).
class DeviceStateTable {
 public:
  // A message whose index is outside 0..kMaxDevices-1 is not kept (false).
  bool store(const thx_msgs::device_state_t& m) {
    if (m.device < 0 || m.device >= kMaxDevices) return false;
    std::lock_guard<std::mutex> lock(mutex_);
    latest_[std::size_t(m.device)] = m;
    return true;
  }
  std::optional<thx_msgs::device_state_t> latest(int device) const {
    if (device < 0 || device >= kMaxDevices) return std::nullopt;
    std::lock_guard<std::mutex> lock(mutex_);
    return latest_[std::size_t(device)];
  }

 private:
  mutable std::mutex mutex_;
  std::array<std::optional<thx_msgs::device_state_t>, kMaxDevices> latest_{};
};

}  // namespace thx::client
