#pragma once
// Does a recorded session (`hapticd --record FILE`, an LCM log) run on the scene a replaying client
// loads? hapticd --record writes its hello (scene_name, texture_fingerprint) before the first tick
// and at each scene switch; a client that renders the log offline (audio-client and
// visual-client --replay-log) compares each recorded hello naming a scene it loads with that
// scene's own fingerprint, as the live check of scene_check.hpp does with hapticd's hello
// (docs/clients.md §7, "Same scene").
#include <cstdint>
#include <string>
#include <vector>

#include "base/error.hpp"
#include "thx_client/scene_check.hpp"

namespace thx::client {

// A recorded hello: when, and which scene.
struct LoggedScene {
  std::int64_t utime = 0;
  SceneIdentity scene;
};

// The log's THX_HELLO events in log order (none in a log without hellos). Throws thx_msgs::LogError
// naming the file and event: not an LCM log, a hello that does not decode.
std::vector<LoggedScene> loggedScenes(const std::string& log_path);

// Raised when a recorded hello names `mine.name` with another texture fingerprint.
class LoggedSceneMismatch : public Error {
 public:
  explicit LoggedSceneMismatch(const std::string& message) : Error(Kind::Config, message) {}
};

// Every hello of `logged` naming `mine.name` must carry `mine.texture_fingerprint`; hellos naming
// other scenes are not this scene's business. The first mismatch throws LoggedSceneMismatch naming
// the log file, the scene, both fingerprints and the hello's time (and, with offers_allow, points to
// --allow-different-scene), unless allow_different_scene, when the message is returned (a warning;
// "" when every hello matched).
std::string checkLoggedScene(const std::vector<LoggedScene>& logged, const SceneIdentity& mine,
                             const std::string& log_path, bool allow_different_scene = false, bool offers_allow = true);

}  // namespace thx::client
