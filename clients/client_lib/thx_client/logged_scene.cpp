#include "thx_client/logged_scene.hpp"

#include "textures/texture_fingerprint.hpp"
#include "thx_msgs/hello_t.hpp"
#include "thx_msgs/log_reader.hpp"

namespace thx::client {

std::vector<LoggedScene> loggedScenes(const std::string& log_path) {
  std::vector<LoggedScene> out;
  thx_msgs::forEachLogMessage<thx_msgs::hello_t>(log_path, thx_msgs::kChannelHello,
                                                  [&](const thx_msgs::hello_t& h, const thx_msgs::LogPosition&) {
                                                    out.push_back({h.utime, sceneOf(h)});
                                                  });
  return out;
}

std::string checkLoggedScene(const std::vector<LoggedScene>& logged, const SceneIdentity& mine,
                             const std::string& log_path, bool allow_different_scene, bool offers_allow) {
  for (const LoggedScene& l : logged) {
    if (l.scene.name != mine.name || l.scene.texture_fingerprint == mine.texture_fingerprint) continue;
    std::string message = log_path + ": texture mismatch: the recorded session ran scene '" + mine.name +
                          "' with texture fingerprint " + tex::formatFingerprint(l.scene.texture_fingerprint) +
                          " (hello at utime " + std::to_string(l.utime) + "), this client's '" + mine.name +
                          "' has " + tex::formatFingerprint(mine.texture_fingerprint);
    if (allow_different_scene) return message + "; rendering it anyway (--allow-different-scene)";
    throw LoggedSceneMismatch(message + ": the scene file or its texture changed since the recording; replay with the "
                              "recording's files" +
                              (offers_allow ? ", or pass --allow-different-scene to render it anyway" : ""));
  }
  return {};
}

}  // namespace thx::client
