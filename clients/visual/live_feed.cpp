#include "clients/visual/live_feed.hpp"

namespace thx::visual {

namespace {
client::AppOptions appOptions(const std::string& lcm_url, double connect_timeout_s, const client::SceneIdentity& mine,
                              bool allow_different_scene, int device) {
  client::AppOptions o;
  o.client_id = "visual";
  o.lcm_url = lcm_url;
  o.connect_timeout_s = connect_timeout_s;
  o.scene = mine;
  o.allow_different_scene = allow_different_scene;
  o.client.device = device;
  return o;
}
}  // namespace

LiveFeed::LiveFeed(const std::string& lcm_url, double rate_hz, double connect_timeout_s, const client::SceneIdentity& mine,
                   bool allow_different_scene, int device)
    : app_(appOptions(lcm_url, connect_timeout_s, mine, allow_different_scene, device)), poses_(app_.lcm()) {
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

LiveView LiveFeed::poll() {
  app_.client().poll(0);
  return liveViewOf(app_.client().latestDeviceState(), poses_.latest());
}

std::optional<client::SceneIdentity> LiveFeed::takeSceneSwitch() {
  if (app_.client().sceneChanges() == scene_changes_seen_ || !app_.client().serverScene()) return std::nullopt;
  scene_changes_seen_ = app_.client().sceneChanges();
  return *app_.client().serverScene();
}

}  // namespace thx::visual
