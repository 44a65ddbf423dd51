#include "thx_client/scene_check.hpp"

#include "textures/texture_fingerprint.hpp"

namespace thx::client {

namespace {

std::string describe(const SceneIdentity& s) {
  return "scene '" + s.name + "' (texture fingerprint " + tex::formatFingerprint(s.texture_fingerprint) + ")";
}

}  // namespace

SceneIdentity sceneOf(const thx_msgs::hello_t& hello) {
  return {hello.scene_name, static_cast<std::uint64_t>(hello.texture_fingerprint)};
}

SceneCheck checkScene(const SceneIdentity& server, const SceneIdentity& mine, bool allow_different_scene,
                      const std::string& server_label) {
  SceneCheck check;
  if (server.name == mine.name && server.texture_fingerprint == mine.texture_fingerprint) return check;
  const bool same_name = server.name == mine.name;
  check.message = std::string(same_name ? "texture mismatch: " : "scene mismatch: ") + server_label + " runs " +
                  describe(server) + ", this client " + describe(mine);
  if (allow_different_scene) {
    check.verdict = SceneVerdict::DiffersAllowed;
    check.message += "; continuing, as a different scene was allowed (--allow-different-scene)";
    return check;
  }
  check.verdict = SceneVerdict::Differs;
  check.message += same_name ? ": the scene files or their textures differ between the two (another version of "
                               "the file on one host?); give both the same files, or pass --allow-different-scene "
                               "to differ on purpose"
                             : "; start the client on the server's scene (--scene " + server.name +
                                   "), or pass --allow-different-scene to differ on purpose";
  return check;
}

SceneCheck checkScene(const thx_msgs::hello_t& hello, const SceneIdentity& mine, bool allow_different_scene) {
  return checkScene(sceneOf(hello), mine, allow_different_scene,
                    hello.server_name.empty() ? std::string("hapticd") : hello.server_name);
}

}  // namespace thx::client
