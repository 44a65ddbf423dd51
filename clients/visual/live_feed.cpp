#include "clients/visual/live_feed.hpp"

#include "thx_client/devices.hpp"

namespace thx::visual {

namespace {
client::AppOptions appOptions(const std::string& lcm_url, double connect_timeout_s, const client::SceneIdentity& mine,
                              bool allow_different_scene, std::optional<int> device) {
  client::AppOptions o;
  o.client_id = "visual";
  o.lcm_url = lcm_url;
  o.connect_timeout_s = connect_timeout_s;
  o.scene = mine;
  o.allow_different_scene = allow_different_scene;
  o.client.device = device.value_or(0);
  return o;
}
}  // namespace

LiveFeed::LiveFeed(const std::string& lcm_url, double rate_hz, double connect_timeout_s, const client::SceneIdentity& mine,
                   bool allow_different_scene, std::optional<int> device)
    : device_(device), app_(appOptions(lcm_url, connect_timeout_s, mine, allow_different_scene, device)), poses_(app_.lcm()) {
  app_.client().subscribe(thx_msgs::Stream::DeviceState, rate_hz);
}

std::optional<thx_msgs::hello_t> LiveFeed::connect(std::string& why) {
  try {
    std::optional<thx_msgs::hello_t> hello = app_.waitForServer();
    if (!hello) why = "stopped while waiting for hapticd";
    scene_changes_seen_ = app_.client().sceneChanges();
    return hello;
  } catch (const Error& e) {
    if (e.kind() != Error::Kind::Io) throw;  // another scene: the user must know
    why = e.what();
    return std::nullopt;
  }
}

std::vector<int> LiveFeed::drawnDevices() {
  if (device_) return {*device_};
  const std::optional<thx_msgs::hello_t> hello = app_.client().latestHello();
  // A hello naming no device (a server before protocol 6) has device 0 only (devices.hpp).
  const int count = hello ? std::max(1, int(client::deviceNames(*hello).size())) : 1;
  std::vector<int> all;
  for (int i = 0; i < count && i < client::kMaxDevices; ++i) all.push_back(i);
  return all;
}

LiveView LiveFeed::poll() {
  app_.client().poll(0);
  std::vector<thx_msgs::device_state_t> states;
  for (const int i : drawnDevices()) {
    if (std::optional<thx_msgs::device_state_t> s = app_.client().latestDeviceState(i)) states.push_back(*s);
  }
  return liveViewOf(states, poses_.latest());
}

std::optional<client::SceneIdentity> LiveFeed::takeSceneSwitch() {
  if (app_.client().sceneChanges() == scene_changes_seen_ || !app_.client().serverScene()) return std::nullopt;
  scene_changes_seen_ = app_.client().sceneChanges();
  return *app_.client().serverScene();
}

}  // namespace thx::visual
