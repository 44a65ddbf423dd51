#pragma once
// visual-client --live: the device states (tip, proxy, contact) of every device hapticd's hello
// names, or of one, through the client kit at the client's own rate, the physics client's poses (THX_PHYSICS_POSES, no handshake), and the
// server's scene switches from its hellos (docs/clients.md §3.3).
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "clients/visual/live_view.hpp"
#include "thx_client/app.hpp"
#include "thx_client/subscriber.hpp"

namespace thx::visual {

struct LiveCounts {
  std::int64_t steps = 0;     // loop steps at --rate
  std::int64_t drawn = 0;     // frames drawn
  std::int64_t skipped = 0;   // steps whose view equalled the last frame drawn: nothing drawn
  std::int64_t scene_switches = 0;
};

class LiveFeed {
 public:
  // `mine`: the scene this client loaded; waitForServer() refuses another (the kit's check)
  // unless `allow_different_scene` (then a warning on stderr). `device`: the one device whose pen
  // is drawn (ClientOptions::device: connect() throws when hapticd has no such device); nullopt:
  // every device the newest hello names (the kit follows device 0).
  LiveFeed(const std::string& lcm_url, double rate_hz, double connect_timeout_s, const client::SceneIdentity& mine,
           bool allow_different_scene = false, std::optional<int> device = std::nullopt);

  // Waits for hapticd's hello. nullopt and `why` when none came within the timeout (or a stop
  // signal came); throws thx::Error when the server runs another scene or has no such device.
  std::optional<thx_msgs::hello_t> connect(std::string& why);
  // Handles the traffic queued now (no wait) and returns what a frame would show: the newest state
  // of each device drawn (Client::latestDeviceState(i)), in index order.
  LiveView poll();
  // The scene the server switched to since the last call (the newest of several), else nullopt.
  std::optional<client::SceneIdentity> takeSceneSwitch();
  client::ClientApp& app() { return app_; }

 private:
  std::vector<int> drawnDevices();

  std::optional<int> device_;
  client::ClientApp app_;
  client::PhysicsPosesSubscriber poses_;
  std::uint64_t scene_changes_seen_ = 0;
};

}  // namespace thx::visual
